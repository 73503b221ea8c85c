// SPDX-License-Identifier: MIT
// planted.glsl - one more planted comment, in a shader.
// the median 18.1 degrees when every change was a surface
