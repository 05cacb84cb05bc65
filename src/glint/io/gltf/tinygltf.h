#pragma once
// tinygltf (libtinygltf-dev) as Glint configures it. Every file that includes tiny_gltf.h must
// see the same settings (they change inline code in the header), so they include this instead.
// Internal to glint/io.
//
// - No stb_image and no image writing in tinygltf: Glint decodes the images materials use
//   itself (io/image/texture_io.h), with its size limits and sRGB handling, and never writes glTF.
// - No external images: tinygltf only records their URIs, and Glint reads the files it needs.
// - No file system: Glint reads the glTF file itself and serves external buffers through its
//   own callbacks, which check limits and honour LoadLimits::readFiles.

#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#define TINYGLTF_NO_FS
#include <tiny_gltf.h>
