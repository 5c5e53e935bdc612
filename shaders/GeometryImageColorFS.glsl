//VTK::Color::Impl
  // Colour by chart, level or attribute (tcLODMapper::ColorMode) in place of the actor's, before
  // VTK mixes in the edges and lights it.
  if (tcColorMode != 0)
  {
    ambientColor = ambientIntensity * tcColorVSOutput;
    diffuseColor = diffuseIntensity * tcColorVSOutput;
  }
