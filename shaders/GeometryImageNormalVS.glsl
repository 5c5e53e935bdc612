//VTK::Light::Dec
// After VTK's normal declarations (the light ones follow them): VTK's normal code, when lighting
// needs one, transforms the normal image's normal (GeometryImageDecVS.glsl says why).
#define normalMC tcNormalMC
