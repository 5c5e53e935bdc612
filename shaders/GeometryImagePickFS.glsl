  // Replaces the picking tag in the selector's cell passes, tag and all, so that VTK's own
  // id (which counts grid triangles) is not written as well. The cell id of tc::LodDrawList: the
  // entry's first id plus the triangle's index in its grid; gl_PrimitiveID restarts with every
  // instance, which draws tcCopies grids.
  int idx = texelFetch(tcDrawList, tcEntryVSOutput).w +
    (gl_PrimitiveID % tcGridPrimitives) / tcPrimitivesPerTriangle;
  if (tcPickHigh != 0)
  {
    idx = (idx >> 24) & 255;
  }
  gl_FragData[0] = vec4(float(idx % 256) / 255.0, float((idx / 256) % 256) / 255.0,
    float((idx / 65536) % 256) / 255.0, 1.0);
