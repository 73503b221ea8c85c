// SPDX-License-Identifier: MIT
// tinygltf_impl.cpp — tinygltf's implementation, compiled only when snell is
// configured with -DSNELL_TINYGLTF_DIR (tinygltf used header-only from a source
// tree, as an NDK app vendors it); otherwise the library links libtinygltf.so.
// The image loaders are left out (TINYGLTF_NO_STB_IMAGE*, set for every file
// of the library so that mesh_gltf.cpp sees the same declarations).
#define TINYGLTF_IMPLEMENTATION
#include <tiny_gltf.h>
