//VTK::CustomBegin::Impl
  // Each instance of the draw is one character: its palette has its place in the crowd folded
  // in (an instance matrix times each skinning matrix), so skinning also places it.
  vec4 tcSkinnedMC = vertexMC;
  vec3 tcSkinnedNormalMC = tcNormalMC;
  tcSkin(gl_InstanceID * tcJointCount, tcJoints, tcWeights, tcSkinnedMC, tcSkinnedNormalMC);
  // VTK's code after this point (positions, normals, clipping) reads vertexMC and normalMC
  // (when it lights), which are vertex attributes and cannot be assigned: the names now mean
  // the posed ones.
#define vertexMC tcSkinnedMC
#define normalMC tcSkinnedNormalMC
