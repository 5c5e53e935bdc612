//VTK::PositionVC::Dec
// Triangular geometry images (Feng et al. 2010, section 6.2): every chart is drawn from the grid
// of its level, shared by all charts; vertexMC.xy carries the grid sample (i, j) and nothing else.
// Everything else comes from buffer textures, read with texelFetch (no filtering).
uniform samplerBuffer tcPositions;  // one texel per atlas texel of every image: xyz, attribute
uniform samplerBuffer tcNormals;    // the same for the normal image
uniform isamplerBuffer tcOrigins;   // per (chart, image): (texel of sample (0, 0), signed row stride)
uniform isamplerBuffer tcCharts;    // per chart: (first origin, maxLevel, 0, 0)
uniform isamplerBuffer tcDrawList;  // per drawn (instance, chart): (chart, instance, levels, cell id)
uniform samplerBuffer tcInstances;  // per instance: the rows of its 3 x 4 transform
uniform int tcLevel;                // the level of every chart of this draw call
uniform int tcDrawOffset;           // first draw-list entry of this draw call
uniform int tcDrawEnd;              // and the end of its entries
uniform int tcCopies;               // charts per instance: copies of the grid, k in vertexMC.z
uniform int tcStitching;            // 0 draws every chart unstitched (to show what eq. 8 mends)
uniform int tcColorMode;            // 0 the actor's colour, 1 per chart, 2 per level, 3 attribute,
                                    // 4 texture, 5 vertex colours (tcLODMapper::ColorModes)
uniform samplerBuffer tcColors;     // the lookup table, 256 colours over tcRange
uniform int tcSkinning;             // 1: pose by the skin (shaders/SkinningVS.glsl)
uniform samplerBuffer tcSkinJoints; // per atlas texel: its 4 joints (integers as floats)
uniform samplerBuffer tcSkinWeights; // and their weights
uniform int tcJointCount;           // joints per palette: instance k's starts at joint k * this
uniform vec2 tcRange;

out vec3 tcColorVSOutput;
out vec2 tcTexCoordVSOutput;  // mode 4: the sample's texture coordinates
out vec4 tcCaptureVSOutput;   // model position and chart: read back by transform feedback
out vec4 tcCaptureGridVSOutput; // (i, j, level, instance) of the same vertex
flat out int tcEntryVSOutput;   // the draw-list entry (the picking pass's cell ids), -1 padding

// The sample's position and normal, computed first in main (GeometryImageBeginVS.glsl).
vec4 tcPositionMC;
vec3 tcNormalMC;

// The grid sample (i, j, copy) itself. From here on vertexMC names the sample's position, so
// that VTK's own code for every setting (lighting or not, clipping planes, flat normals, edges,
// depth peeling, picking) transforms the surface and not the grid; normalMC follows in
// GeometryImageNormalVS.glsl, after VTK declares it.
vec4 tcGridMC()
{
  return vertexMC;
}
#define vertexMC tcPositionMC

// Eq. (8) of Feng et al.: a vertex on side k of a chart at level n whose neighbour across k is at
// a coarser level m moves to parameter t - (t mod 2^(n - m)) of the same side; the rule and its
// parameterization are those of tc::stitchedGridPoint (geometry_image_mesh.h), which this must
// match vertex for vertex.
ivec2 tcStitch(int n, ivec3 m, ivec2 ij)
{
  int big = 1 << n;
  int side = -1;
  int t = 0;
  if (ij.y == 0 && ij.x != 0 && ij.x != big) { side = 0; t = ij.x; }
  else if (ij.x + ij.y == big && ij.x != 0 && ij.y != 0) { side = 1; t = ij.y; }
  else if (ij.x == 0 && ij.y != 0 && ij.y != big) { side = 2; t = big - ij.y; }
  if (side < 0 || m[side] >= n || tcStitching == 0)
  {
    return ij;
  }
  int step = 1 << (n - m[side]);
  t -= t % step;
  if (side == 0) { return ivec2(t, 0); }
  if (side == 1) { return ivec2(big - t, t); }
  return ivec2(0, big - t);
}

// Golden-ratio hues at saturation 0.55, value 0.95: the colours tcColorMaps gives labels.
vec3 tcLabelColor(int label)
{
  float h = fract(0.618033988749895 * float(label));
  vec3 k = clamp(abs(mod(h * 6.0 + vec3(0.0, 4.0, 2.0), 6.0) - 3.0) - 1.0, 0.0, 1.0);
  return mix(vec3(1.0), k, 0.55) * 0.95;
}

// tcvtk::lod::PackTexels' r * 65536 + g * 256 + b (0 .. 255 each) as a colour.
vec3 tcUnpackRgb(float code)
{
  // The code is an exact integer; adding 0.5 first would round odd codes above 2^23 up.
  int rgb = int(code);
  return vec3(float((rgb >> 16) & 255), float((rgb >> 8) & 255), float(rgb & 255)) / 255.0;
}
