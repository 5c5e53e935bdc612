// SPDX-License-Identifier: BSD-3-Clause
#include "tcLODMapper.h"

#include "tcAtlasConversion.h"
#include "tcLODAtlasData.h"
#include "tcLODSkinning.h"

#include "tc/common/array_names.h"
#include "tc/gim/atlas.h"
#include "tc/gim/lod_selection.h"

#include "tcGeometryImageBeginVS.h"
#include "tcGeometryImageColorDecFS.h"
#include "tcGeometryImageColorDecGS.h"
#include "tcGeometryImageColorFS.h"
#include "tcGeometryImageColorGS.h"
#include "tcGeometryImageDecVS.h"
#include "tcGeometryImageNormalVS.h"
#include "tcGeometryImagePickFS.h"
#include "tcSkinningVS.h"

#include <vtkActor.h>
#include <vtkCommand.h>
#include <vtkFloatArray.h>
#include <vtkHardwareSelector.h>
#include <vtkInformation.h>
#include <vtkIntArray.h>
#include <vtkMath.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkOpenGLBufferObject.h>
#include <vtkOpenGLHelper.h>
#include <vtkOpenGLIndexBufferObject.h>
#include <vtkOpenGLPolyDataMapper.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkOpenGLShaderCache.h>
#include <vtkOpenGLState.h>
#include <vtkOpenGLVertexArrayObject.h>
#include <vtkOpenGLVertexBufferObject.h>
#include <vtkPolyData.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>
#include <vtkScalarsToColors.h>
#include <vtkShader.h>
#include <vtkShaderProgram.h>
#include <vtkTextureObject.h>
#include <vtkTextureUnitManager.h>
#include <vtkTransformFeedback.h>
#include <vtkWeakPointer.h>
#include <vtk_glew.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <exception>
#include <map>
#include <string>
#include <vector>

namespace
{
/// One buffer texture: the data in a buffer object, read by texelFetch through a texture.
/// vtkTextureObject's CreateTextureBuffer finds no format for 4-component buffers in VTK 9.2, so
/// the texture is made here with glTexBuffer; its unit comes from VTK's texture unit manager.
struct BufferTexture
{
  vtkNew<vtkOpenGLBufferObject> buffer;
  GLuint texture = 0;
  int unit = -1;

  template <typename T>
  void Upload(const std::vector<T>& values, bool integer)
  {
    // An empty buffer texture is not allowed; one zero texel stands in. The values themselves
    // go up uncopied: the draw list is uploaded every frame.
    static const T zeros[4] = {};
    this->buffer->Upload(values.empty() ? zeros : values.data(), values.empty() ? 4 : values.size(),
      vtkOpenGLBufferObject::TextureBuffer);
    if (this->texture == 0)
    {
      glGenTextures(1, &this->texture);
    }
    glBindTexture(GL_TEXTURE_BUFFER, this->texture);
    glTexBuffer(GL_TEXTURE_BUFFER, integer ? GL_RGBA32I : GL_RGBA32F,
      static_cast<GLuint>(this->buffer->GetHandle()));
    glBindTexture(GL_TEXTURE_BUFFER, 0);
  }

  int Activate(vtkOpenGLRenderWindow* window)
  {
    this->unit = window->GetTextureUnitManager()->Allocate();
    window->GetState()->vtkglActiveTexture(GL_TEXTURE0 + static_cast<GLenum>(this->unit));
    glBindTexture(GL_TEXTURE_BUFFER, this->texture);
    return this->unit;
  }

  void Deactivate(vtkOpenGLRenderWindow* window)
  {
    if (this->unit >= 0)
    {
      window->GetState()->vtkglActiveTexture(GL_TEXTURE0 + static_cast<GLenum>(this->unit));
      glBindTexture(GL_TEXTURE_BUFFER, 0);
      window->GetTextureUnitManager()->Free(this->unit);
      this->unit = -1;
    }
  }

  void Release()
  {
    if (this->texture != 0)
    {
      glDeleteTextures(1, &this->texture);
      this->texture = 0;
    }
    this->buffer->ReleaseGraphicsResources();
  }
};

/// The shader replacements of shaders/ (STYLE.md 7): (stage, VTK tag, text). Each text but the
/// picking one starts with its tag again, so that VTK's own code still goes there (after ours
/// for declarations and the begin of main, before it for the colour). They are applied by the
/// grid mapper (ReplaceShaderValues below) and not through the actor's vtkShaderProperty, which
/// is the user's: replacements of their own there still apply, before ours.
struct Replacement
{
  vtkShader::Type stage;
  const char* tag;
  const char* text;
};
const std::array<Replacement, 8> kReplacements{ {
  { vtkShader::Vertex, "//VTK::PositionVC::Dec", tcSkinningVS },
  { vtkShader::Vertex, "//VTK::PositionVC::Dec", tcGeometryImageDecVS },
  { vtkShader::Vertex, "//VTK::Light::Dec", tcGeometryImageNormalVS },
  { vtkShader::Vertex, "//VTK::CustomBegin::Impl", tcGeometryImageBeginVS },
  { vtkShader::Geometry, "//VTK::Color::Dec", tcGeometryImageColorDecGS },
  { vtkShader::Geometry, "//VTK::Color::Impl", tcGeometryImageColorGS },
  { vtkShader::Fragment, "//VTK::Normal::Dec", tcGeometryImageColorDecFS },
  { vtkShader::Fragment, "//VTK::Color::Impl", tcGeometryImageColorFS },
} };

/// Applies one replacement (its first occurrence) to a stage's source, when that has the tag.
void Substitute(std::map<vtkShader::Type, vtkShader*>& shaders, vtkShader::Type stage,
  const char* tag, const char* text)
{
  vtkShader* shader = shaders[stage];
  if (!shader)
  {
    return;
  }
  std::string source = shader->GetSource();
  if (vtkShaderProgram::Substitute(source, tag, text, false))
  {
    shader->SetSource(source);
  }
}

/// The shader's samplers of the buffer textures, in the order of Internals::textures().
const std::array<const char*, 10> kTextureUniforms{ "tcPositions", "tcNormals", "tcOrigins",
  "tcCharts", "tcDrawList", "tcInstances", "tcColors", "tcSkinJoints", "tcSkinWeights", "tcBones" };

/// What a colour mode reads from the atlas: the attribute (-1: none) and how it rides in the
/// texels, or why the mode cannot be drawn (`missing`, "" when it can).
struct ColorSource
{
  int attribute = -1;
  tcvtk::lod::TexelColor color = tcvtk::lod::TexelColor::None;
  std::string missing;
};

/// The atlas's base-colour texture, null when it has none.
const tc::AtlasTexture* BaseColorTexture(const tc::Atlas& atlas)
{
  for (const tc::AtlasTexture& texture : atlas.textures)
  {
    if (texture.name == tc::kAtlasBaseColorTexture)
    {
      return &texture;
    }
  }
  return nullptr;
}

/// The source of ColorMode `mode`; ColorAttribute `name` rides along in the other modes that
/// leave the fourth components free, so that switching to ColorByAttribute uploads nothing.
ColorSource FindColorSource(const tc::Atlas& atlas, int mode, const std::string& name)
{
  using tcvtk::lod::TexelColor;
  ColorSource source;
  if (mode == tcLODMapper::ColorByTexture)
  {
    source.attribute = tc::findAttribute(atlas, tc::kAtlasTextureCoordinates);
    source.color = TexelColor::Texture;
    if (source.attribute < 0 || !BaseColorTexture(atlas))
    {
      source = { -1, TexelColor::None,
        "ColorByTexture: the atlas has no base-colour texture (build it from a textured mesh "
        "with tcGeometryImages' KeepAppearance on)" };
    }
    return source;
  }
  if (mode == tcLODMapper::ColorByVertexColors)
  {
    source.attribute = tc::findAttribute(atlas, tc::kColors);
    source.color = TexelColor::Rgb;
    if (source.attribute < 0 ||
      atlas.attributes[static_cast<size_t>(source.attribute)].components < 3)
    {
      source = { -1, TexelColor::None,
        "ColorByVertexColors: the atlas has no Colors attribute of 3 or 4 components (build it "
        "from a mesh with vertex colours, tcGeometryImages' KeepAppearance on)" };
    }
    return source;
  }
  const int attribute = tc::findAttribute(atlas, name);
  if (attribute >= 2)
  {
    source = { attribute, TexelColor::Scalar, "" };
  }
  else if (!name.empty())
  {
    source.missing = "ColorAttribute '" + name + "' is not an attribute of the atlas (" +
      tcvtk::lod::OtherAttributes(atlas) + ")";
  }
  return source;
}

/// Row-major 4 x 4 identity: the one instance drawn without SetInstanceMatrices.
const std::vector<double> kIdentity{ 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };
} // namespace

using namespace tcvtk::lod;

/// The OpenGL side: a polydata mapper whose input is the grids of every level, drawing them
/// instanced per level with the owner's buffer textures bound. Being a vtkOpenGLPolyDataMapper it
/// keeps VTK's lighting, colour, representation and shader replacements.
class tcLODGridMapper : public vtkOpenGLPolyDataMapper
{
public:
  static tcLODGridMapper* New();
  vtkTypeMacro(tcLODGridMapper, vtkOpenGLPolyDataMapper);
  tcLODMapper* Owner = nullptr;

protected:
  tcLODGridMapper()
  {
    // Vertices carry grid coordinates, not positions: VTK must not shift and scale them.
    this->SetVBOShiftScaleMethod(vtkOpenGLVertexBufferObject::DISABLE_SHIFT_SCALE);
    this->ScalarVisibilityOff();
    this->StaticOn();
  }
  void RenderPieceDraw(vtkRenderer* ren, vtkActor* act) override;
  void UpdateShaders(vtkOpenGLHelper& cellBO, vtkRenderer* ren, vtkActor* act) override;
  void ReplaceShaderValues(
    std::map<vtkShader::Type, vtkShader*> shaders, vtkRenderer* ren, vtkActor* act) override;
  void ReplaceShaderPicking(
    std::map<vtkShader::Type, vtkShader*> shaders, vtkRenderer* ren, vtkActor* act) override;
  // The grid has no texture coordinates: the actor's textures are left out (tcLODMapper warns).
  bool HaveTextures(vtkActor*) override { return false; }
  unsigned int GetNumberOfTextures(vtkActor*) override { return 0; }
  std::vector<std::pair<vtkTexture*, std::string>> GetTextures(vtkActor*) override { return {}; }

private:
  bool Capturing(vtkRenderer* ren, vtkActor* act);
  void LinkCapture(vtkOpenGLHelper& cellBO, vtkRenderer* ren, vtkActor* act);
  int UploadColorTable(std::array<double, 2>& range);
  void SetFrameUniforms(vtkShaderProgram* program, vtkRenderer* ren, vtkActor* act);
  size_t BeginCapture(GLenum mode);
  void DrawLevels(vtkShaderProgram* program, GLenum mode, size_t perTriangle);
  void EndCapture(size_t vertices);
};
vtkStandardNewMacro(tcLODGridMapper);

struct tcLODMapper::Internals
{
  vtkNew<tcLODGridMapper> gridMapper;
  tc::Atlas atlas;
  tc::LodCharts charts;
  bool valid = false;
  vtkMTimeType atlasTime = 0;
  std::string error;

  /// Levels 0 .. maxLevel, one after another: points (i, j, 0), triangles in grid order
  /// (tc::gridVertexIndex), the vertex buffer every chart of a level shares.
  vtkNew<vtkPolyData> grid;
  std::vector<int64_t> gridTriangleStart; // per level, + 1
  std::vector<int32_t> gridCopies;        // per level: charts one instance of the draw draws

  std::vector<double> instances = kIdentity;
  vtkTimeStamp instanceTime;
  std::vector<int32_t> chartLevels; // empty: choose per view
  std::vector<int32_t> levels;      // instances x charts, the last frame's choice
  tc::LodDrawList list;
  bool haveSelection = false;
  double selectionSeconds = 0.0;
  double drawListSeconds = 0.0;

  BufferTexture positions, normals, origins, chartTable, drawList, instanceRows, colors;
  BufferTexture skinJoints, skinWeights, bones;
  /// The buffer textures, in the order of kTextureUniforms.
  std::array<BufferTexture*, 10> textures()
  {
    return { &positions, &normals, &origins, &chartTable, &drawList, &instanceRows, &colors,
      &skinJoints, &skinWeights, &bones };
  }

  /// Skinning: the skinned boxes, the instances' poses and palettes (tcLODSkinning.h).
  SkinnedAtlas skinned;
  std::vector<double> instanceTimes;   // empty: AnimationTime for all
  std::vector<int> instanceAnimations; // empty: Animation for all
  vtkTimeStamp poseTime;               // when the palettes were last computed
  bool posed = false;                  // whether they pose this frame (GetSkinned)
  vtkTimeStamp bonesTime;              // when they last went up
  std::string warnedAnimation;         // the unknown Animation last reported
  vtkTimeStamp uploadTime;
  std::string uploadedAttribute; // the ColorAttribute asked for at the last upload
  int uploadedMode = -1;         // and the ColorMode
  bool attributeFound = false;   // whether the fourth components hold what that mode shows
  /// The base-colour texture (ColorByTexture), or one white texel: the sampler always has a
  /// texture of its own type on a unit of its own, as OpenGL requires of every draw.
  vtkNew<vtkTextureObject> texture;
  std::array<double, 2> attributeRange{ 0.0, 1.0 };
  vtkOpenGLRenderWindow* uploadWindow = nullptr;

  vtkNew<vtkTransformFeedback> capture;
  vtkNew<vtkFloatArray> captured;

  /// The window whose context holds the buffer textures (and the grid mapper's buffers), and
  /// the observer that frees them before that window goes.
  vtkWeakPointer<vtkOpenGLRenderWindow> window;
  unsigned long deleteObserver = 0;
  bool warnedTextures = false;
  bool warnedPointSelection = false;
  bool warnedCapture = false;

  double bounds[6] = { 0, -1, 0, -1, 0, -1 };
  vtkTimeStamp boundsTime;
};

vtkStandardNewMacro(tcLODMapper);

tcLODMapper::tcLODMapper()
  : Internal(new Internals)
{
  this->Internal->gridMapper->Owner = this;
  this->Internal->gridMapper->SetInputData(this->Internal->grid);
  this->Internal->captured->SetNumberOfComponents(8);
  this->Internal->capture->AddVarying(vtkTransformFeedback::Color_RGBA_F, "tcCaptureVSOutput");
  this->Internal->capture->AddVarying(vtkTransformFeedback::Color_RGBA_F, "tcCaptureGridVSOutput");
  this->Internal->capture->SetPrimitiveMode(GL_TRIANGLES);
}

tcLODMapper::~tcLODMapper()
{
  Internals& in = *this->Internal;
  if (in.window)
  {
    vtkOpenGLRenderWindow* window = in.window;
    window->PushContext();
    this->ReleaseGraphicsResources(window);
    window->PopContext();
  }
  this->SetColorAttribute(nullptr);
  this->SetAnimation(nullptr);
}

void tcLODMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "LODBias: " << this->LODBias << "\n";
  os << indent << "ErrorTarget: " << this->ErrorTarget << "\n";
  os << indent << "FreezeLOD: " << this->FreezeLOD << "\n";
  os << indent << "Culling: " << this->Culling << "\n";
  os << indent << "Stitching: " << this->Stitching << "\n";
  os << indent << "FixedLevel: " << this->FixedLevel << "\n";
  os << indent << "ColorMode: " << this->ColorMode << "\n";
  os << indent << "ColorAttribute: " << (this->ColorAttribute ? this->ColorAttribute : "(none)")
     << "\n";
  os << indent << "Instances: " << this->GetNumberOfInstances() << "\n";
  os << indent << "Skinning: " << this->Skinning << "\n";
  os << indent << "Animation: " << (this->Animation ? this->Animation : "(first)") << "\n";
  os << indent << "AnimationTime: " << this->AnimationTime << "\n";
}

int tcLODMapper::FillInputPortInformation(int, vtkInformation* info)
{
  // Any data object: ToAtlas explains what an atlas is when it gets something else.
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataObject");
  return 1;
}

void tcLODMapper::SetInputData(vtkDataObject* atlas)
{
  this->SetInputDataInternal(0, atlas);
  if (!atlas)
  {
    this->ReleaseAtlas();
  }
}

void tcLODMapper::ReleaseAtlas()
{
  // The converted atlas is a full copy of the input's texels: nothing of it is kept once the
  // input is gone (the GPU copy goes with the graphics resources).
  Internals& in = *this->Internal;
  in.atlas = tc::Atlas();
  in.valid = false;
  in.atlasTime = 0;
  in.list = tc::LodDrawList();
  in.haveSelection = false;
}

void tcLODMapper::SetChartLevels(vtkIntArray* levels)
{
  std::vector<int32_t> values;
  if (levels)
  {
    values.assign(levels->GetPointer(0), levels->GetPointer(0) + levels->GetNumberOfTuples());
  }
  if (values != this->Internal->chartLevels)
  {
    this->Internal->chartLevels = values;
    this->Internal->haveSelection = false;
    this->Modified();
  }
}

void tcLODMapper::SetInstanceMatrices(vtkDataArray* matrices)
{
  std::vector<double> values = kIdentity;
  if (matrices)
  {
    if (matrices->GetNumberOfComponents() != 16 || matrices->GetNumberOfTuples() < 1)
    {
      vtkErrorMacro("SetInstanceMatrices needs 16 components per tuple (a row-major 4 x 4 "
                    "matrix) and at least one tuple; got "
        << matrices->GetNumberOfComponents() << " components and " << matrices->GetNumberOfTuples()
        << " tuples. The instances are unchanged.");
      return;
    }
    values.resize(static_cast<size_t>(16 * matrices->GetNumberOfTuples()));
    for (vtkIdType t = 0; t < matrices->GetNumberOfTuples(); ++t)
    {
      matrices->GetTuple(t, values.data() + 16 * t);
    }
  }
  for (double v : values)
  {
    if (!std::isfinite(v))
    {
      vtkErrorMacro("SetInstanceMatrices: a matrix holds NaN or infinity; the instances are "
                    "unchanged.");
      return;
    }
  }
  this->Internal->instances = values;
  this->Internal->instanceTime.Modified();
  this->Internal->haveSelection = false;
  this->Modified();
}

void tcLODMapper::SetInstanceTimes(vtkDataArray* seconds)
{
  std::vector<double> values;
  for (vtkIdType t = 0; seconds && t < seconds->GetNumberOfTuples(); ++t)
  {
    values.push_back(seconds->GetComponent(t, 0));
    if (!std::isfinite(values.back()))
    {
      vtkErrorMacro("SetInstanceTimes: time " << t
                                              << " is NaN or infinite; the times are "
                                                 "unchanged.");
      return;
    }
  }
  if (values != this->Internal->instanceTimes)
  {
    this->Internal->instanceTimes = values;
    this->Modified();
  }
}

void tcLODMapper::SetInstanceAnimations(vtkIntArray* animations)
{
  std::vector<int> values;
  for (vtkIdType t = 0; animations && t < animations->GetNumberOfTuples(); ++t)
  {
    values.push_back(animations->GetValue(t * animations->GetNumberOfComponents()));
  }
  if (values != this->Internal->instanceAnimations)
  {
    this->Internal->instanceAnimations = values;
    this->Modified();
  }
}

bool tcLODMapper::GetSkinned() const
{
  return this->Internal->posed;
}

int tcLODMapper::GetNumberOfInstances() const
{
  return static_cast<int>(this->Internal->instances.size() / 16);
}

vtkFloatArray* tcLODMapper::GetCapturedVertices()
{
  return this->Internal->captured;
}

vtkIdType tcLODMapper::GetTrianglesDrawn() const
{
  return static_cast<vtkIdType>(this->Internal->list.triangles);
}

vtkIdType tcLODMapper::GetChartsDrawn() const
{
  return static_cast<vtkIdType>(this->Internal->list.entries.size() / 4);
}

vtkIdType tcLODMapper::GetChartsAtLevel(int level) const
{
  const auto& counts = this->Internal->list.chartsPerLevel;
  return level >= 0 && level < static_cast<int>(counts.size())
    ? static_cast<vtkIdType>(counts[static_cast<size_t>(level)])
    : 0;
}

double tcLODMapper::GetSelectionSeconds() const
{
  return this->Internal->selectionSeconds;
}

double tcLODMapper::GetDrawListSeconds() const
{
  return this->Internal->drawListSeconds;
}

void tcLODMapper::GetLevels(vtkIntArray* levels) const
{
  const Internals& in = *this->Internal;
  const int instances = this->GetNumberOfInstances();
  const size_t nc = in.atlas.charts.size();
  levels->SetNumberOfComponents(instances);
  levels->SetNumberOfTuples(
    in.levels.size() == nc * static_cast<size_t>(instances) ? static_cast<vtkIdType>(nc) : 0);
  for (vtkIdType c = 0; c < levels->GetNumberOfTuples(); ++c)
  {
    for (int i = 0; i < instances; ++i)
    {
      levels->SetTypedComponent(
        c, i, in.levels[static_cast<size_t>(i) * nc + static_cast<size_t>(c)]);
    }
  }
}

vtkIdType tcLODMapper::GetNumberOfCharts() const
{
  return this->Internal->valid ? static_cast<vtkIdType>(this->Internal->atlas.charts.size()) : 0;
}

bool tcLODMapper::UpdateAtlas()
{
  Internals& in = *this->Internal;
  if (!this->Static && this->GetInputAlgorithm())
  {
    this->GetInputAlgorithm()->Update();
  }
  vtkDataObject* input = this->GetInputDataObject(0, 0);
  if (!input)
  {
    this->ReleaseAtlas();
    return false;
  }
  if (input->GetMTime() == in.atlasTime)
  {
    return in.valid;
  }
  in.atlasTime = input->GetMTime();
  in.valid = tcvtk::ToAtlas(input, in.atlas, in.error);
  in.haveSelection = false;
  if (!in.valid)
  {
    in.list = tc::LodDrawList();
    vtkErrorMacro("Cannot draw the atlas: " << in.error << ".");
    return false;
  }
  try
  {
    // Refuses levels above 15 (the draw list packs levels in 4 bits) and malformed errors.
    in.charts = tc::LodCharts::fromAtlas(in.atlas);
    PrepareSkinnedAtlas(in.atlas, in.skinned);
  }
  catch (const std::exception& e)
  {
    in.valid = false;
    in.list = tc::LodDrawList();
    vtkErrorMacro("Cannot draw the atlas: " << e.what() << ".");
    return false;
  }
  BuildGrids(in.atlas.maxLevel(), in.grid, in.gridTriangleStart, in.gridCopies);
  return true;
}

void tcLODMapper::UploadAtlas(vtkRenderer* ren)
{
  Internals& in = *this->Internal;
  auto* window = static_cast<vtkOpenGLRenderWindow*>(ren->GetRenderWindow());
  const std::string attributeName = this->ColorAttribute ? this->ColorAttribute : "";
  if (in.uploadWindow == window && in.uploadTime > in.grid->GetMTime() &&
    in.uploadTime > in.instanceTime && in.uploadedAttribute == attributeName &&
    in.uploadedMode == this->ColorMode)
  {
    return;
  }
  const tc::Atlas& atlas = in.atlas;
  // What the colour mode shows rides in the fourth components of the texels.
  const ColorSource source = FindColorSource(atlas, this->ColorMode, attributeName);
  if (!source.missing.empty())
  {
    vtkErrorMacro(<< source.missing << "; the actor's colour is used.");
  }
  const AtlasTexels texels = PackTexels(atlas, source.attribute, source.color);
  this->UploadTexture(window, source.color == TexelColor::Texture);
  std::vector<int32_t> origins;
  std::vector<int32_t> charts;
  PackChartTable(atlas, texels.imageBase, origins, charts);
  in.positions.Upload(texels.position, false);
  in.normals.Upload(texels.normal, false);
  in.origins.Upload(origins, true);
  in.chartTable.Upload(charts, true);
  in.instanceRows.Upload(InstanceRows(in.instances), false);
  const int skin = tc::findAttribute(atlas, tc::kAtlasSkin);
  const SkinTexels skinTexels = in.skinned.valid ? PackSkin(atlas, skin) : SkinTexels();
  in.skinJoints.Upload(skinTexels.joints, false);
  in.skinWeights.Upload(skinTexels.weights, false);
  in.attributeRange = source.color == TexelColor::Scalar
    ? AttributeRange(atlas, texels.position)
    : std::array<double, 2>{ VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX };
  in.uploadedAttribute = attributeName;
  in.uploadedMode = this->ColorMode;
  in.attributeFound = source.attribute >= 0;
  in.uploadWindow = window;
  in.uploadTime.Modified();
}

void tcLODMapper::UploadTexture(vtkOpenGLRenderWindow* window, bool baseColor)
{
  // Mipmapped and repeated, as glTF's default sampler and an engine draw it.
  vtkTextureObject* texture = this->Internal->texture;
  texture->SetContext(window);
  texture->SetWrapS(vtkTextureObject::Repeat);
  texture->SetWrapT(vtkTextureObject::Repeat);
  texture->SetMagnificationFilter(vtkTextureObject::Linear);
  texture->SetMinificationFilter(
    baseColor ? vtkTextureObject::LinearMipmapLinear : vtkTextureObject::Nearest);
  texture->SetGenerateMipmap(baseColor);
  static const uint8_t white[4] = { 255, 255, 255, 255 };
  const tc::AtlasTexture* image = baseColor ? BaseColorTexture(this->Internal->atlas) : nullptr;
  texture->Create2DFromRaw(image ? static_cast<unsigned int>(image->width) : 1,
    image ? static_cast<unsigned int>(image->height) : 1, 4, VTK_UNSIGNED_CHAR,
    const_cast<uint8_t*>(image ? image->rgba.data() : white));
}

void tcLODMapper::UpdatePalettes()
{
  Internals& in = *this->Internal;
  const bool posed = this->Skinning && in.skinned.valid;
  if (posed == in.posed && in.poseTime > this->GetMTime() && in.poseTime > in.instanceTime &&
    in.poseTime > in.grid->GetMTime())
  {
    return;
  }
  in.posed = posed;
  in.poseTime.Modified();
  if (!posed)
  {
    in.skinned.palettes.clear();
    return;
  }
  std::string error;
  const int chosen =
    tc::findAnimation(in.atlas.rig.animations, this->Animation ? this->Animation : "", error);
  if (!error.empty() && error != in.warnedAnimation)
  {
    vtkErrorMacro("Animation: " << error << "; the bind pose is drawn.");
  }
  in.warnedAnimation = error;
  const size_t instances = static_cast<size_t>(this->GetNumberOfInstances());
  const int animationCount = static_cast<int>(in.atlas.rig.animations.size());
  std::vector<int> animations(instances, chosen);
  std::vector<double> times(instances, this->AnimationTime);
  for (size_t i = 0; i < instances; ++i)
  {
    if (i < in.instanceAnimations.size() && in.instanceAnimations[i] >= 0)
    {
      // An index past the rig's animations poses the bind pose, as an unknown name does.
      animations[i] = in.instanceAnimations[i] < animationCount ? in.instanceAnimations[i] : -1;
    }
    if (i < in.instanceTimes.size())
    {
      times[i] = in.instanceTimes[i];
    }
  }
  PoseInstances(in.atlas, animations, times, in.skinned);
}

void tcLODMapper::UploadBones()
{
  Internals& in = *this->Internal;
  // Released with the other graphics resources (texture 0): up again, posed or not.
  if (in.bones.texture != 0 && in.bonesTime > in.poseTime)
  {
    return;
  }
  in.bones.Upload(in.skinned.palettes, false);
  in.bonesTime.Modified();
}

void tcLODMapper::SelectLevels(vtkRenderer* ren, vtkActor* act)
{
  Internals& in = *this->Internal;
  const int instances = this->GetNumberOfInstances();
  const size_t nc = in.atlas.charts.size();
  if (this->FreezeLOD && in.haveSelection)
  {
    return;
  }
  const auto start = std::chrono::steady_clock::now();
  in.levels.resize(nc * static_cast<size_t>(instances));
  if (!in.chartLevels.empty() || this->FixedLevel >= 0)
  {
    if (!in.chartLevels.empty() && in.chartLevels.size() != nc)
    {
      vtkErrorMacro("ChartLevels has " << in.chartLevels.size() << " values but the atlas has "
                                       << nc << " charts; drawing every chart at its finest.");
    }
    FixedLevels(in.atlas, in.chartLevels, this->FixedLevel, instances, in.levels);
  }
  else
  {
    tc::LodOptions options;
    options.bias = this->LODBias;
    options.errorPixels = this->ErrorTarget;
    options.cull = this->Culling;
    ViewLevels(ren, act, in.charts, in.instances, options, nc, in.levels,
      in.posed ? in.skinned.posedBox.data() : nullptr,
      in.posed ? in.skinned.posedArea.data() : nullptr);
  }
  const auto selected = std::chrono::steady_clock::now();
  // The levels above are clamped to each chart's range, which is all buildDrawList checks.
  tc::buildDrawList(in.charts, in.levels.data(), instances, in.list);
  in.drawList.Upload(in.list.entries, true);
  in.haveSelection = true;
  in.selectionSeconds = std::chrono::duration<double>(selected - start).count();
  in.drawListSeconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - selected).count();
}

void tcLODMapper::Render(vtkRenderer* ren, vtkActor* act)
{
  if (ren->GetRenderWindow()->CheckAbortStatus())
  {
    return;
  }
  this->InvokeEvent(vtkCommand::StartEvent, nullptr);
  const bool ready = this->UpdateAtlas();
  this->InvokeEvent(vtkCommand::EndEvent, nullptr);
  if (!ready || this->Internal->atlas.charts.empty())
  {
    return;
  }
  this->WarnAboutSettings(ren, act);
  this->UseWindow(static_cast<vtkOpenGLRenderWindow*>(ren->GetRenderWindow()));
  this->UploadAtlas(ren);
  this->UpdatePalettes();
  this->UploadBones();
  this->SelectLevels(ren, act);
  tcLODGridMapper* grid = this->Internal->gridMapper;
  grid->SetClippingPlanes(this->ClippingPlanes);
  grid->SetResolveCoincidentTopology(this->GetResolveCoincidentTopology());
  grid->Render(ren, act);
}

void tcLODMapper::WarnAboutSettings(vtkRenderer* ren, vtkActor* act)
{
  Internals& in = *this->Internal;
  vtkProperty* property = act->GetProperty();
  if (!in.warnedTextures && (act->GetTexture() || property->GetNumberOfTextures() > 0))
  {
    vtkWarningMacro("The actor has a texture, which tcLODMapper does not draw: the grids it "
                    "draws have no texture coordinates. Colour by the atlas's own texture "
                    "(ColorMode ColorByTexture), or by ColorMode and ColorAttribute.");
    in.warnedTextures = true;
  }
  vtkHardwareSelector* selector = ren->GetSelector();
  if (!in.warnedPointSelection && selector &&
    selector->GetFieldAssociation() == vtkDataObject::FIELD_ASSOCIATION_POINTS)
  {
    vtkWarningMacro("tcLODMapper draws nothing for a point selection: grid samples are no "
                    "points of a dataset. Select cells (vtkDataObject::FIELD_ASSOCIATION_CELLS) "
                    "and map each cell id to its chart and level with LocateCell.");
    in.warnedPointSelection = true;
  }
}

void tcLODMapper::UseWindow(vtkOpenGLRenderWindow* window)
{
  Internals& in = *this->Internal;
  if (in.window == window)
  {
    return;
  }
  // Another window: its context shares nothing with the last one, so what that one holds is
  // freed there and everything goes up again here (each switch costs a full upload).
  if (in.window)
  {
    vtkOpenGLRenderWindow* previous = in.window;
    previous->PushContext();
    this->ReleaseGraphicsResources(previous);
    previous->PopContext();
  }
  in.window = window;
  in.deleteObserver =
    window->AddObserver(vtkCommand::DeleteEvent, this, &tcLODMapper::WindowDeleted);
}

void tcLODMapper::WindowDeleted(vtkObject* window, unsigned long, void*)
{
  // Before the window's destructor, while its context still exists.
  auto* gl = static_cast<vtkOpenGLRenderWindow*>(window);
  gl->PushContext();
  this->ReleaseGraphicsResources(gl);
  gl->PopContext();
}

void tcLODGridMapper::ReplaceShaderValues(
  std::map<vtkShader::Type, vtkShader*> shaders, vtkRenderer* ren, vtkActor* act)
{
  for (const Replacement& r : kReplacements)
  {
    Substitute(shaders, r.stage, r.tag, r.text);
  }
  this->Superclass::ReplaceShaderValues(shaders, ren, act);
}

void tcLODGridMapper::ReplaceShaderPicking(
  std::map<vtkShader::Type, vtkShader*> shaders, vtkRenderer* ren, vtkActor* act)
{
  // The cell passes write tc::LodDrawList's cell ids (VTK's count grid triangles).
  if (this->LastSelectionState == vtkHardwareSelector::CELL_ID_LOW24 ||
    this->LastSelectionState == vtkHardwareSelector::CELL_ID_HIGH24)
  {
    Substitute(shaders, vtkShader::Fragment, "//VTK::Picking::Impl", tcGeometryImagePickFS);
  }
  this->Superclass::ReplaceShaderPicking(shaders, ren, act);
}

bool tcLODGridMapper::Capturing(vtkRenderer* ren, vtkActor* act)
{
  tcLODMapper::Internals& in = *this->Owner->Internal;
  if (!this->Owner->CaptureVertices)
  {
    return false;
  }
  // Transform feedback reads the vertex shader's outputs, which a geometry shader hides.
  if (this->DrawingEdges(ren, act) || this->HaveWideLines(ren, act))
  {
    if (!in.warnedCapture)
    {
      vtkWarningMacro("CaptureVertices reads nothing back while the actor draws edges or wide "
                      "lines (a geometry shader); turn EdgeVisibility off and LineWidth to 1.");
      in.warnedCapture = true;
    }
    return false;
  }
  return true;
}

void tcLODGridMapper::UpdateShaders(vtkOpenGLHelper& cellBO, vtkRenderer* ren, vtkActor* act)
{
  // vtkOpenGLPolyDataMapper::UpdateShaders (VTK 9.2), except that a program that does not build
  // (a user's replacement that does not compile) leaves no program and nothing drawn: VTK's
  // dereferences the missing program on the next try.
  auto* window = static_cast<vtkOpenGLRenderWindow*>(ren->GetRenderWindow());
  cellBO.VAO->Bind();
  this->LastBoundBO = &cellBO;
  if (this->GetNeedToRebuildShaders(cellBO, ren, act))
  {
    vtkNew<vtkShader> vertex, geometry, fragment;
    vertex->SetType(vtkShader::Vertex);
    geometry->SetType(vtkShader::Geometry);
    fragment->SetType(vtkShader::Fragment);
    std::map<vtkShader::Type, vtkShader*> shaders{ { vtkShader::Vertex, vertex },
      { vtkShader::Geometry, geometry }, { vtkShader::Fragment, fragment } };
    this->BuildShaders(shaders, ren, act);
    vtkShaderProgram* program = window->GetShaderCache()->ReadyShaderProgram(shaders);
    if (program != cellBO.Program || (program && program->GetMTime() > cellBO.AttributeUpdateTime))
    {
      cellBO.Program = program;
      cellBO.VAO->ReleaseGraphicsResources();
    }
    cellBO.ShaderSourceTime.Modified();
  }
  else if (cellBO.Program)
  {
    window->GetShaderCache()->ReadyShaderProgram(cellBO.Program);
    if (cellBO.Program->GetMTime() > cellBO.AttributeUpdateTime)
    {
      cellBO.VAO->ReleaseGraphicsResources();
    }
  }
  if (!cellBO.Program)
  {
    return;
  }
  this->LinkCapture(cellBO, ren, act);
  this->SetCustomUniforms(cellBO, act);
  this->SetMapperShaderParameters(cellBO, ren, act);
  this->SetPropertyShaderParameters(cellBO, ren, act);
  this->SetCameraShaderParameters(cellBO, ren, act);
  this->SetLightingShaderParameters(cellBO, ren, act);
  this->InvokeEvent(vtkCommand::UpdateShaderEvent, cellBO.Program);
}

void tcLODGridMapper::LinkCapture(vtkOpenGLHelper& cellBO, vtkRenderer* ren, vtkActor* act)
{
  if (!this->Capturing(ren, act) ||
    cellBO.Program->GetTransformFeedback() == this->Owner->Internal->capture.Get())
  {
    return;
  }
  // Transform feedback needs its varyings named before the program links: link it again with
  // them (the uniforms and vertex attributes are set after this).
  auto* window = static_cast<vtkOpenGLRenderWindow*>(ren->GetRenderWindow());
  window->GetShaderCache()->ReadyShaderProgram(cellBO.Program, this->Owner->Internal->capture);
  cellBO.VAO->ReleaseGraphicsResources();
  cellBO.ShaderSourceTime.Modified();
}

int tcLODGridMapper::UploadColorTable(std::array<double, 2>& range)
{
  tcLODMapper::Internals& in = *this->Owner->Internal;
  tcLODMapper* owner = this->Owner;
  // ScalarVisibility off draws the actor's colour, as it does for vtkPolyDataMapper.
  int colorMode = owner->GetScalarVisibility() ? owner->ColorMode : tcLODMapper::ColorByActor;
  range = in.attributeRange;
  if ((colorMode == tcLODMapper::ColorByTexture || colorMode == tcLODMapper::ColorByVertexColors) &&
    !in.attributeFound)
  {
    colorMode = tcLODMapper::ColorByActor;
  }
  if (colorMode == tcLODMapper::ColorByAttribute)
  {
    if (!in.attributeFound)
    {
      colorMode = tcLODMapper::ColorByActor;
    }
    vtkScalarsToColors* table = owner->GetLookupTable();
    table->Build(); // a lookup table maps nothing before it is built
    if (owner->GetUseLookupTableScalarRange())
    {
      range = { table->GetRange()[0], table->GetRange()[1] };
    }
    std::vector<float> colors(4 * 256);
    for (int i = 0; i < 256; ++i)
    {
      double rgb[3];
      table->GetColor(range[0] + (range[1] - range[0]) * i / 255.0, rgb);
      std::copy(rgb, rgb + 3, colors.begin() + 4 * i);
      colors[static_cast<size_t>(4 * i + 3)] = 1.0f;
    }
    in.colors.Upload(colors, false);
  }
  else if (in.colors.texture == 0)
  {
    in.colors.Upload(std::vector<float>(4, 0.0f), false);
  }
  return colorMode;
}

size_t tcLODGridMapper::BeginCapture(GLenum mode)
{
  tcLODMapper::Internals& in = *this->Owner->Internal;
  size_t vertices = 0;
  for (size_t n = 0; n + 1 < in.list.levelStart.size() && n < in.gridCopies.size(); ++n)
  {
    const int64_t count = in.list.levelStart[n + 1] - in.list.levelStart[n];
    const int64_t draws = (count + in.gridCopies[n] - 1) / in.gridCopies[n];
    vertices += static_cast<size_t>(draws) * 3 *
      static_cast<size_t>(in.gridTriangleStart[n + 1] - in.gridTriangleStart[n]);
  }
  in.capture->SetNumberOfVertices(vertices);
  in.capture->SetPrimitiveMode(mode == GL_TRIANGLES ? GL_TRIANGLES : GL_POINTS);
  in.capture->BindBuffer();
  return vertices;
}

void tcLODGridMapper::DrawLevels(vtkShaderProgram* program, GLenum mode, size_t perTriangle)
{
  tcLODMapper::Internals& in = *this->Owner->Internal;
  const size_t levels = std::min(in.list.levelStart.size(), in.gridTriangleStart.size()) - 1;
  // Primitives per grid triangle: its 3 indices make 1 triangle, 3 points or (6) 3 lines.
  const size_t perPrimitive = mode == GL_TRIANGLES ? 3 : mode == GL_LINES ? 2 : 1;
  const int primitivesPerTriangle = static_cast<int>(perTriangle / perPrimitive);
  program->SetUniformi("tcPrimitivesPerTriangle", primitivesPerTriangle);
  for (size_t n = 0; n < levels; ++n)
  {
    const int64_t first = in.list.levelStart[n];
    const int64_t count = in.list.levelStart[n + 1] - first;
    if (count == 0)
    {
      continue;
    }
    const int32_t copies = in.gridCopies[n];
    program->SetUniformi("tcLevel", static_cast<int>(n));
    program->SetUniformi("tcDrawOffset", static_cast<int>(first));
    program->SetUniformi("tcDrawEnd", static_cast<int>(first + count));
    program->SetUniformi("tcCopies", copies);
    program->SetUniformi("tcGridPrimitives", primitivesPerTriangle << (2 * n));
    const size_t offset = perTriangle * static_cast<size_t>(in.gridTriangleStart[n]);
    const size_t indices =
      perTriangle * static_cast<size_t>(in.gridTriangleStart[n + 1] - in.gridTriangleStart[n]);
    glDrawElementsInstanced(mode, static_cast<GLsizei>(indices), GL_UNSIGNED_INT,
      reinterpret_cast<const GLvoid*>(offset * sizeof(GLuint)),
      static_cast<GLsizei>((count + copies - 1) / copies));
  }
}

void tcLODGridMapper::EndCapture(size_t vertices)
{
  tcLODMapper::Internals& in = *this->Owner->Internal;
  in.capture->ReadBuffer();
  const auto* data = static_cast<const float*>(in.capture->GetBufferData());
  in.captured->SetNumberOfTuples(static_cast<vtkIdType>(vertices));
  if (data)
  {
    std::copy(data, data + 8 * vertices, in.captured->GetPointer(0));
  }
  in.capture->ReleaseBufferData();
}

void tcLODGridMapper::SetFrameUniforms(vtkShaderProgram* program, vtkRenderer* ren, vtkActor* act)
{
  tcLODMapper::Internals& in = *this->Owner->Internal;
  std::array<double, 2> range;
  const int colorMode = this->UploadColorTable(range);
  auto* window = static_cast<vtkOpenGLRenderWindow*>(ren->GetRenderWindow());
  const auto textures = in.textures();
  for (size_t t = 0; t < textures.size(); ++t)
  {
    program->SetUniformi(kTextureUniforms[t], textures[t]->Activate(window));
  }
  in.texture->Activate();
  program->SetUniformi("tcTexture", in.texture->GetTextureUnit());
  program->SetUniformi("tcStitching", this->Owner->Stitching ? 1 : 0);
  program->SetUniformi("tcSkinning", in.posed ? 1 : 0);
  program->SetUniformi("tcJointCount", in.skinned.joints);
  program->SetUniformi("tcColorMode", colorMode);
  const float rangeValues[2] = { static_cast<float>(range[0]), static_cast<float>(range[1]) };
  program->SetUniform2f("tcRange", rangeValues);
  program->SetUniformi(
    "tcPickHigh", this->LastSelectionState == vtkHardwareSelector::CELL_ID_HIGH24 ? 1 : 0);
  vtkHardwareSelector* selector = ren->GetSelector();
  if (selector)
  {
    // The selector renders the high 24 bits of the ids only when some id needs them.
    selector->UpdateMaximumCellId(static_cast<vtkIdType>(in.list.triangles) - 1);
  }
  if (act->GetProperty()->GetRepresentation() == VTK_WIREFRAME && !this->HaveWideLines(ren, act))
  {
    window->GetState()->vtkglLineWidth(act->GetProperty()->GetLineWidth());
  }
}

void tcLODGridMapper::RenderPieceDraw(vtkRenderer* ren, vtkActor* act)
{
  tcLODMapper::Internals& in = *this->Owner->Internal;
  vtkOpenGLHelper& tris = this->Primitives[PrimitiveTris];
  const int64_t gridTriangles = in.gridTriangleStart.back();
  vtkHardwareSelector* selector = ren->GetSelector();
  if (tris.IBO->IndexCount == 0 || gridTriangles == 0 || in.list.entries.empty() ||
    (selector && selector->GetFieldAssociation() == vtkDataObject::FIELD_ASSOCIATION_POINTS))
  {
    return;
  }
  // Surface: 3 indices per grid triangle; wireframe: 6 (its three edges); points: 3.
  const size_t perTriangle = tris.IBO->IndexCount / static_cast<size_t>(gridTriangles);
  if (perTriangle * static_cast<size_t>(gridTriangles) != tris.IBO->IndexCount)
  {
    vtkErrorMacro("Unexpected index buffer for the grids (" << tris.IBO->IndexCount
                                                            << " indices); nothing drawn.");
    return;
  }
  const GLenum mode = static_cast<GLenum>(
    this->GetOpenGLMode(act->GetProperty()->GetRepresentation(), PrimitiveTris));
  this->UpdateShaders(tris, ren, act);
  vtkShaderProgram* program = tris.Program;
  if (!program)
  {
    return;
  }
  this->SetFrameUniforms(program, ren, act);

  // One instanced draw per level, read back by transform feedback when asked.
  const bool capturing = this->Capturing(ren, act);
  const size_t captured = capturing ? this->BeginCapture(mode) : 0;
  tris.IBO->Bind();
  this->DrawLevels(program, mode, perTriangle);
  tris.IBO->Release();
  if (capturing)
  {
    this->EndCapture(captured);
  }
  auto* window = static_cast<vtkOpenGLRenderWindow*>(ren->GetRenderWindow());
  for (BufferTexture* texture : in.textures())
  {
    texture->Deactivate(window);
  }
  in.texture->Deactivate();
}

double* tcLODMapper::GetBounds()
{
  Internals& in = *this->Internal;
  if (!this->UpdateAtlas() || in.atlas.charts.empty())
  {
    vtkMath::UninitializeBounds(this->Bounds);
    return this->Bounds;
  }
  this->UpdatePalettes();
  if (in.boundsTime < in.grid->GetMTime() || in.boundsTime < in.instanceTime ||
    in.boundsTime < in.poseTime)
  {
    try
    {
      // Posed: the posed samples', or for a large crowd the posed boxes' (PosedBounds).
      const std::array<double, 6> b = in.posed ? PosedBounds(in.atlas, in.skinned, in.instances)
                                               : tc::drawnBounds(in.atlas, in.instances);
      std::copy(b.begin(), b.end(), in.bounds);
    }
    catch (const std::exception& e)
    {
      vtkErrorMacro("Cannot bound the atlas: " << e.what() << ".");
      vtkMath::UninitializeBounds(in.bounds);
    }
    in.boundsTime.Modified();
  }
  std::copy(in.bounds, in.bounds + 6, this->Bounds);
  return this->Bounds;
}

bool tcLODMapper::LocateCell(vtkIdType cellId, vtkIdType location[4]) const
{
  const tc::LodTriangle t = tc::locateTriangle(this->Internal->list, cellId);
  location[0] = t.instance;
  location[1] = t.chart;
  location[2] = t.level;
  location[3] = static_cast<vtkIdType>(t.triangle);
  return t.chart >= 0;
}

void tcLODMapper::ReleaseGraphicsResources(vtkWindow* window)
{
  Internals& in = *this->Internal;
  // The resources live in one window's context: a request from another window finds none.
  if (window && in.window && window != in.window)
  {
    return;
  }
  for (BufferTexture* texture : in.textures())
  {
    texture->Release();
  }
  in.texture->ReleaseGraphicsResources(in.window ? in.window.Get() : window);
  in.capture->ReleaseGraphicsResources();
  in.gridMapper->ReleaseGraphicsResources(window);
  if (in.window)
  {
    in.window->RemoveObserver(in.deleteObserver);
  }
  in.window = nullptr;
  in.uploadWindow = nullptr;
  in.haveSelection = false;
}
