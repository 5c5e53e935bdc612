//VTK::Normal::Dec
in vec3 tcColorVSOutput;
uniform int tcColorMode;
