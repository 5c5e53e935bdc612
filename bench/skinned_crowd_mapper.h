// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class tcSkinnedCrowdMapper
 * @brief The peer of bench_skinned_crowd: a crowd of one skinned mesh drawn at full resolution,
 * posed by linear blend skinning in the vertex shader (shaders/SkinningVS.glsl, the rule
 * tcLODMapper skins with), every character in one instanced draw.
 *
 * What a game engine does without level of detail: the input mesh in one vertex buffer shared by
 * every character, its point arrays SkinIndices (4 joint ids) and SkinWeights (4 weights) as
 * vertex attributes, and each frame the palettes of the characters to draw (those in view) in
 * one buffer texture, tcBones. Draw instance k is character k and skins with palette k, whose
 * matrices have the character's place in the crowd folded in (instance matrix times skinning
 * matrix), so the same fetches skin and place it.
 *
 * Why one instanced draw rather than an actor per character sharing one mapper (the static
 * crowd's peer in bench_lod_rendering): VTK spends tens of microseconds per actor setting its
 * uniforms and state, which would count against the peer in a comparison about triangles, and
 * tcLODMapper draws its whole crowd with a few instanced draws too. Culling is left to the
 * caller, which knows each character's bounding sphere in every pose: only characters in view
 * are given palettes.
 *
 * The input must be triangles with the two skin arrays and point normals named "Normals"
 * (vtkPolyDataNormals' name), which the vertex shader turns with the skin. SetPalettes does not
 * modify the mapper (which would rebuild its shaders and buffers each frame): it is meant to be
 * called before every render.
 */
#ifndef tcSkinnedCrowdMapper_h
#define tcSkinnedCrowdMapper_h

#include <vtkNew.h>
#include <vtkOpenGLBufferObject.h> // for vtkNew
#include <vtkOpenGLPolyDataMapper.h>

#include <vector>

class vtkOpenGLRenderWindow;

class tcSkinnedCrowdMapper : public vtkOpenGLPolyDataMapper
{
public:
  static tcSkinnedCrowdMapper* New();
  vtkTypeMacro(tcSkinnedCrowdMapper, vtkOpenGLPolyDataMapper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The characters of the next frames: `palettes` holds one palette per character, `joints`
  /// joints each of tc::kPaletteFloats floats (tc::appendPaletteRows of its matrices).
  void SetPalettes(const std::vector<float>& palettes, int joints);
  int GetNumberOfCharacters() const { return this->Characters; }

  /// The bounds of the whole crowd in every pose: what the renderer culls the actor by and
  /// resets the camera to (the input mesh's own bounds say nothing of where characters stand).
  void SetCrowdBounds(const double bounds[6]);
  double* GetBounds() override { return this->CrowdBounds; }
  void GetBounds(double bounds[6]) override { this->vtkAbstractMapper3D::GetBounds(bounds); }

  void ReleaseGraphicsResources(vtkWindow* window) override;

protected:
  tcSkinnedCrowdMapper();
  ~tcSkinnedCrowdMapper() override;

  void ReplaceShaderValues(
    std::map<vtkShader::Type, vtkShader*> shaders, vtkRenderer* ren, vtkActor* act) override;
  void RenderPieceDraw(vtkRenderer* ren, vtkActor* act) override;

private:
  tcSkinnedCrowdMapper(const tcSkinnedCrowdMapper&) = delete;
  void operator=(const tcSkinnedCrowdMapper&) = delete;

  /// Uploads the palettes when they changed, binds tcBones to a free texture unit; its unit.
  int BindPalettes(vtkOpenGLRenderWindow* window);
  void UnbindPalettes(vtkOpenGLRenderWindow* window);

  std::vector<float> Palettes;
  int Joints = 0;
  int Characters = 0;
  bool PalettesUploaded = false;
  double CrowdBounds[6] = { 0, -1, 0, -1, 0, -1 };

  vtkNew<vtkOpenGLBufferObject> PaletteBuffer;
  unsigned int PaletteTexture = 0;
  int PaletteUnit = -1;
};

#endif
