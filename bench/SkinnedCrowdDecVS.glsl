//VTK::PositionVC::Dec
// tcSkinnedCrowdMapper (bench/skinned_crowd_mapper.h): the input mesh's skin as vertex
// attributes (point arrays SkinIndices and SkinWeights), its normals as an attribute of its own
// (VTK declares normalMC only when it lights the surface), and the joints of one palette, so
// that instance k of the draw reads palette k of tcBones.
in vec4 tcJoints;
in vec4 tcWeights;
in vec3 tcNormalMC;
uniform int tcJointCount;
