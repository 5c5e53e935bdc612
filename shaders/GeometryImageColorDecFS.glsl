//VTK::Normal::Dec
in vec3 tcColorVSOutput;
in vec2 tcTexCoordVSOutput;
uniform sampler2D tcTexture;         // the atlas's base-colour texture (1 white texel without)
flat in int tcEntryVSOutput;
uniform int tcColorMode;
uniform isamplerBuffer tcDrawList;
uniform int tcGridPrimitives;        // primitives of one chart's grid at this draw's level
uniform int tcPrimitivesPerTriangle; // 1 (surface), 3 (wireframe: edges; points: corners)
uniform int tcPickHigh;              // 1 in the selector's pass of the cell ids' high 24 bits
