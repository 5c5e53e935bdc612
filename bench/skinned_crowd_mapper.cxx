// SPDX-License-Identifier: BSD-3-Clause
#include "skinned_crowd_mapper.h"

#include "tc/common/array_names.h"
#include "tc/skinning/skin.h"

#include "tcBenchSkinnedCrowdBeginVS.h"
#include "tcBenchSkinnedCrowdDecVS.h"
#include "tcBenchSkinningVS.h"

#include <vtkActor.h>
#include <vtkObjectFactory.h>
#include <vtkOpenGLHelper.h>
#include <vtkOpenGLIndexBufferObject.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkOpenGLState.h>
#include <vtkOpenGLVertexBufferObject.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>
#include <vtkShader.h>
#include <vtkShaderProgram.h>
#include <vtkTextureUnitManager.h>
#include <vtk_glew.h>

#include <algorithm>

vtkStandardNewMacro(tcSkinnedCrowdMapper);

tcSkinnedCrowdMapper::tcSkinnedCrowdMapper()
{
  // Skinning matrices act on the file's coordinates: VTK must not shift and scale them.
  this->SetVBOShiftScaleMethod(vtkOpenGLVertexBufferObject::DISABLE_SHIFT_SCALE);
  this->MapDataArrayToVertexAttribute(
    "tcJoints", tc::kSkinIndices, vtkDataObject::FIELD_ASSOCIATION_POINTS, -1);
  this->MapDataArrayToVertexAttribute(
    "tcWeights", tc::kSkinWeights, vtkDataObject::FIELD_ASSOCIATION_POINTS, -1);
  this->MapDataArrayToVertexAttribute(
    "tcNormalMC", "Normals", vtkDataObject::FIELD_ASSOCIATION_POINTS, -1);
  this->ScalarVisibilityOff();
  this->StaticOn();
}

tcSkinnedCrowdMapper::~tcSkinnedCrowdMapper() = default;

void tcSkinnedCrowdMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Characters: " << this->Characters << "\n";
  os << indent << "Joints: " << this->Joints << "\n";
  os << indent << "CrowdBounds: " << this->CrowdBounds[0] << " " << this->CrowdBounds[1] << " "
     << this->CrowdBounds[2] << " " << this->CrowdBounds[3] << " " << this->CrowdBounds[4] << " "
     << this->CrowdBounds[5] << "\n";
}

void tcSkinnedCrowdMapper::SetPalettes(const std::vector<float>& palettes, int joints)
{
  const size_t perCharacter = static_cast<size_t>(std::max(joints, 1)) * tc::kPaletteFloats;
  this->Palettes = palettes;
  this->Joints = std::max(joints, 0);
  this->Characters = joints > 0 ? static_cast<int>(palettes.size() / perCharacter) : 0;
  this->PalettesUploaded = false;
}

void tcSkinnedCrowdMapper::SetCrowdBounds(const double bounds[6])
{
  std::copy(bounds, bounds + 6, this->CrowdBounds);
  this->Modified();
}

void tcSkinnedCrowdMapper::ReleaseGraphicsResources(vtkWindow* window)
{
  if (this->PaletteTexture != 0)
  {
    glDeleteTextures(1, &this->PaletteTexture);
    this->PaletteTexture = 0;
  }
  this->PaletteBuffer->ReleaseGraphicsResources();
  this->PalettesUploaded = false;
  this->Superclass::ReleaseGraphicsResources(window);
}

void tcSkinnedCrowdMapper::ReplaceShaderValues(
  std::map<vtkShader::Type, vtkShader*> shaders, vtkRenderer* ren, vtkActor* act)
{
  // Both texts start with their tag again, so that VTK's own code still goes there: the
  // shared skinning function, then this mapper's attributes, then VTK's declarations.
  std::string source = shaders[vtkShader::Vertex]->GetSource();
  vtkShaderProgram::Substitute(source, "//VTK::PositionVC::Dec", tcBenchSkinningVS, false);
  vtkShaderProgram::Substitute(source, "//VTK::PositionVC::Dec", tcBenchSkinnedCrowdDecVS, false);
  vtkShaderProgram::Substitute(
    source, "//VTK::CustomBegin::Impl", tcBenchSkinnedCrowdBeginVS, false);
  shaders[vtkShader::Vertex]->SetSource(source);
  this->Superclass::ReplaceShaderValues(shaders, ren, act);
}

int tcSkinnedCrowdMapper::BindPalettes(vtkOpenGLRenderWindow* window)
{
  if (!this->PalettesUploaded)
  {
    this->PaletteBuffer->Upload(this->Palettes, vtkOpenGLBufferObject::TextureBuffer);
    if (this->PaletteTexture == 0)
    {
      glGenTextures(1, &this->PaletteTexture);
    }
    // RGBA32F: one texel per row of a skinning matrix (vtkTextureObject's CreateTextureBuffer
    // finds no 4-component format in VTK 9.2, as tcLODMapper notes).
    glBindTexture(GL_TEXTURE_BUFFER, this->PaletteTexture);
    glTexBuffer(
      GL_TEXTURE_BUFFER, GL_RGBA32F, static_cast<GLuint>(this->PaletteBuffer->GetHandle()));
    glBindTexture(GL_TEXTURE_BUFFER, 0);
    this->PalettesUploaded = true;
  }
  this->PaletteUnit = window->GetTextureUnitManager()->Allocate();
  window->GetState()->vtkglActiveTexture(GL_TEXTURE0 + static_cast<GLenum>(this->PaletteUnit));
  glBindTexture(GL_TEXTURE_BUFFER, this->PaletteTexture);
  return this->PaletteUnit;
}

void tcSkinnedCrowdMapper::UnbindPalettes(vtkOpenGLRenderWindow* window)
{
  window->GetState()->vtkglActiveTexture(GL_TEXTURE0 + static_cast<GLenum>(this->PaletteUnit));
  glBindTexture(GL_TEXTURE_BUFFER, 0);
  window->GetTextureUnitManager()->Free(this->PaletteUnit);
  this->PaletteUnit = -1;
}

void tcSkinnedCrowdMapper::RenderPieceDraw(vtkRenderer* ren, vtkActor* act)
{
  // The input is triangles only (bench_skinned_crowd triangulates it): one instanced draw of
  // the triangle primitives, instance k skinned by palette k.
  vtkOpenGLHelper& tris = this->Primitives[PrimitiveTris];
  if (this->Characters == 0 || tris.IBO->IndexCount == 0)
  {
    return;
  }
  this->UpdateShaders(tris, ren, act);
  vtkShaderProgram* program = tris.Program;
  if (!program)
  {
    return;
  }
  auto* window = static_cast<vtkOpenGLRenderWindow*>(ren->GetRenderWindow());
  program->SetUniformi("tcBones", this->BindPalettes(window));
  program->SetUniformi("tcJointCount", this->Joints);
  const auto mode = static_cast<GLenum>(
    this->GetOpenGLMode(act->GetProperty()->GetRepresentation(), PrimitiveTris));
  tris.IBO->Bind();
  glDrawElementsInstanced(mode, static_cast<GLsizei>(tris.IBO->IndexCount), GL_UNSIGNED_INT,
    nullptr, static_cast<GLsizei>(this->Characters));
  tris.IBO->Release();
  this->UnbindPalettes(window);
}
