// SPDX-License-Identifier: MIT
// tinygltf_impl.cpp — FUZZ BUILDS ONLY (never part of the library, which links
// Debian's libtinygltf.so). Compiling tinygltf's implementation from its header
// lets ASan and libFuzzer's coverage instrument tinygltf's own parsing code.
// Images are never decoded by snell, so stb_image is left out; mesh_gltf.cpp
// must then be compiled with the same -DTINYGLTF_NO_STB_IMAGE* flags.
#define TINYGLTF_IMPLEMENTATION
#include <tiny_gltf.h>
