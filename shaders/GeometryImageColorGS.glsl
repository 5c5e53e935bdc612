//VTK::Color::Impl
    tcColorGSOutput = tcColorVSOutput[i];
    tcEntryGSOutput = tcEntryVSOutput[i];
