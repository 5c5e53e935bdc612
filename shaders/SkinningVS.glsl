//VTK::PositionVC::Dec
// Linear blend skinning in the vertex shader (Feng et al. 2010, 5.2 and 6.2), shared by
// tcLODMapper and every other mapper that skins: one rule, so that they pose alike.
// tcBones holds a palette per pose (a character at its own time of its own animation): 3 texels
// per joint, the rows of its skinning matrix global(joint) * inverseBind(joint) (tc::Matrix4,
// row-major, last row 0 0 0 1), pose after pose (tc::appendPaletteRows).
uniform samplerBuffer tcBones;

// p' = sum_k w_k M[j_k] (p, 1), as tc::skinPoints, weights used as given (they need not sum to
// 1: LBS does not normalize, nor do the files' bakes). The matrices are blended first, then
// applied once; unused slots have weight 0. Normals turn by the blended 3 x 3 part (VTK
// normalizes them after the normal matrix).
void tcSkin(int firstJoint, vec4 joints, vec4 weights, inout vec4 p, inout vec3 n)
{
  vec4 r0 = vec4(0.0);
  vec4 r1 = vec4(0.0);
  vec4 r2 = vec4(0.0);
  for (int k = 0; k < 4; ++k)
  {
    int texel = 3 * (firstJoint + int(joints[k] + 0.5));
    r0 += weights[k] * texelFetch(tcBones, texel);
    r1 += weights[k] * texelFetch(tcBones, texel + 1);
    r2 += weights[k] * texelFetch(tcBones, texel + 2);
  }
  p = vec4(dot(r0, p), dot(r1, p), dot(r2, p), 1.0);
  n = vec3(dot(r0.xyz, n), dot(r1.xyz, n), dot(r2.xyz, n));
}
