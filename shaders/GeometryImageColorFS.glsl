//VTK::Color::Impl
  // Colour by chart, level or attribute (tcLODMapper::ColorMode) in place of the actor's, before
  // VTK mixes in the edges and lights it.
  // The texture's colour takes the actor's place, as vtkTexture's does (which VTK multiplies
  // into the lit colour: the same for a white actor without specular light).
  vec3 tcColor = tcColorMode == 4 ? texture(tcTexture, tcTexCoordVSOutput).rgb : tcColorVSOutput;
  if (tcColorMode != 0)
  {
    ambientColor = ambientIntensity * tcColor;
    diffuseColor = diffuseIntensity * tcColor;
  }
