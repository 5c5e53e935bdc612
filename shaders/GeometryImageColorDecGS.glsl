//VTK::Color::Dec
// A geometry shader (surface with edges, wide lines) passes the colour and entry through.
in vec3 tcColorVSOutput[];
out vec3 tcColorGSOutput;
in vec2 tcTexCoordVSOutput[];
out vec2 tcTexCoordGSOutput;
flat in int tcEntryVSOutput[];
flat out int tcEntryGSOutput;
