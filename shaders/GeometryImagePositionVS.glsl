  vertexVCVSOutput = MCVCMatrix * tcPositionMC;
  gl_Position = MCDCMatrix * tcPositionMC;
