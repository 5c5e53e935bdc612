//VTK::CustomBegin::Impl
  // Which chart, at which level, stitched to which neighbour levels (tc::LodDrawList).
  int tcIndex = tcDrawOffset + gl_InstanceID * tcCopies + int(tcGridMC().z + 0.5);
  // The last instance of a draw may have copies beyond the level's entries: they collapse.
  bool tcPadding = tcIndex >= tcDrawEnd;
  ivec4 tcEntry = texelFetch(tcDrawList, tcPadding ? tcDrawOffset : tcIndex);
  ivec3 tcNeighbor = ivec3((tcEntry.z >> 4) & 15, (tcEntry.z >> 8) & 15, (tcEntry.z >> 12) & 15);
  ivec2 tcGrid = ivec2(tcGridMC().xy + 0.5);
  ivec2 tcSample = tcStitch(tcLevel, tcNeighbor, tcGrid);
  // tc::atlasTexel: the chart's level-n samples sit in image maxLevel - n, at origin + (i, j),
  // or origin - (i, j) for a chart packed turned by 180 degrees (negative stride).
  ivec4 tcChart = texelFetch(tcCharts, tcEntry.x);
  ivec4 tcOrigin = texelFetch(tcOrigins, tcChart.x + tcChart.y - tcLevel);
  int tcTexel = tcOrigin.x + tcSample.y * tcOrigin.y + (tcOrigin.y < 0 ? -tcSample.x : tcSample.x);
  vec4 tcSampleValue = texelFetch(tcPositions, tcTexel);
  vec4 tcP = vec4(tcSampleValue.xyz, 1.0);
  vec4 tcNormalValue = texelFetch(tcNormals, tcTexel);
  vec3 tcN = tcNormalValue.xyz;
  if (tcSkinning != 0)
  {
    // The texel's own skin: the two charts of a shared side hold the same one, so both pose
    // their copies of a side sample alike and the posed atlas stays closed.
    tcSkin(tcEntry.y * tcJointCount, texelFetch(tcSkinJoints, tcTexel),
      texelFetch(tcSkinWeights, tcTexel), tcP, tcN);
  }
  vec4 tcRow0 = texelFetch(tcInstances, 3 * tcEntry.y);
  vec4 tcRow1 = texelFetch(tcInstances, 3 * tcEntry.y + 1);
  vec4 tcRow2 = texelFetch(tcInstances, 3 * tcEntry.y + 2);
  tcPositionMC = tcPadding ? vec4(0.0, 0.0, 0.0, 1.0)
                           : vec4(dot(tcRow0, tcP), dot(tcRow1, tcP), dot(tcRow2, tcP), 1.0);
  // Instance transforms are rigid with a uniform scale, so their 3 x 3 part turns normals too.
  tcNormalMC = vec3(dot(tcRow0.xyz, tcN), dot(tcRow1.xyz, tcN), dot(tcRow2.xyz, tcN));
  tcEntryVSOutput = tcPadding ? -1 : tcIndex;
  tcCaptureVSOutput = vec4(tcPositionMC.xyz, tcPadding ? -1.0 : float(tcEntry.x));
  tcCaptureGridVSOutput = vec4(vec2(tcGrid), float(tcLevel), float(tcEntry.y));
  float tcScaled = clamp((tcSampleValue.w - tcRange.x) / max(tcRange.y - tcRange.x, 1e-30), 0.0, 1.0);
  // A stitched side vertex reads its own chart's texel (tcSample), so a texture seam between
  // two charts keeps each chart's own texture coordinates.
  tcTexCoordVSOutput = vec2(tcSampleValue.w, tcNormalValue.w);
  tcColorVSOutput = tcColorMode == 1 ? tcLabelColor(tcEntry.x)
    : tcColorMode == 2             ? tcLabelColor(tcLevel + 1)
    : tcColorMode == 5             ? tcUnpackRgb(tcSampleValue.w)
                                   : texelFetch(tcColors, int(tcScaled * 255.0 + 0.5)).rgb;
