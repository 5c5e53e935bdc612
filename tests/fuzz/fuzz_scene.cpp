// SPDX-License-Identifier: BSD-3-Clause
// Fuzz target: tc::readScene (Assimp) on any bytes. Assimp picks its importer by the file's
// extension, so the input is written with the extension its first bytes suggest (binary glTF,
// FBX, DirectX X and MD2 have a signature, glTF is JSON), the way a user's file of that kind
// would be named; a mutated signature moves the input to another importer.
#include "fuzz_support.h"
#include "tc/io/scene_io.h"

#include <cstring>

namespace
{
bool startsWith(const uint8_t* data, size_t size, const char* magic)
{
  const size_t n = std::strlen(magic);
  return size >= n && std::memcmp(data, magic, n) == 0;
}

/// The file of the extension the bytes suggest; .glb for bytes that suggest none.
const tcfuzz::InputFile& fileFor(const uint8_t* data, size_t size)
{
  static const tcfuzz::InputFile glb(".glb"), gltf(".gltf"), fbx(".fbx"), x(".x"), md2(".md2");
  if (startsWith(data, size, "Kaydara FBX Binary") || startsWith(data, size, "; FBX"))
  {
    return fbx;
  }
  if (startsWith(data, size, "xof "))
  {
    return x;
  }
  if (startsWith(data, size, "IDP2"))
  {
    return md2;
  }
  if (startsWith(data, size, "{"))
  {
    return gltf;
  }
  return glb;
}
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  const tcfuzz::InputFile& file = fileFor(data, size);
  const std::string& path = file.write(data, size);
  try
  {
    const tc::Scene scene = tc::readScene(path);
    tcfuzz::checkSoup(scene.soup);
    if (scene.meshId.size() != static_cast<size_t>(scene.soup.numPolygons()))
    {
      tcfuzz::InputFile::fail("a scene whose polygons and mesh ids differ in number");
    }
    for (const int32_t id : scene.meshId)
    {
      if (id < 0 || static_cast<size_t>(id) >= scene.meshNames.size())
      {
        tcfuzz::InputFile::fail("a polygon of scene mesh " + std::to_string(id) + " of " +
          std::to_string(scene.meshNames.size()));
      }
    }
  }
  catch (const tc::InputError& error)
  {
    // Assimp's own messages do not name the file; the reader promises a message, no more.
    tcfuzz::checkRefusal(error, path, false);
  }
  return 0;
}
