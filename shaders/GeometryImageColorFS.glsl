//VTK::Normal::Impl
  // Colour by chart or by level (tcLODMapper::ColorMode) in place of the actor's colour.
  if (tcColorMode != 0)
  {
    ambientColor = ambientIntensity * tcColorVSOutput;
    diffuseColor = diffuseIntensity * tcColorVSOutput;
  }
