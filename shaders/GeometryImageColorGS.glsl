//VTK::Color::Impl
    tcColorGSOutput = tcColorVSOutput[i];
    tcTexCoordGSOutput = tcTexCoordVSOutput[i];
    tcEntryGSOutput = tcEntryVSOutput[i];
