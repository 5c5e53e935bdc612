//VTK::Normal::Impl
  // Colour by chart, level or attribute (tcLODMapper::ColorMode) in place of the actor's.
  if (tcColorMode != 0)
  {
    ambientColor = ambientIntensity * tcColorVSOutput;
    diffuseColor = diffuseIntensity * tcColorVSOutput;
  }
