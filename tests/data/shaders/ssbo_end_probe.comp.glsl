// Writes uValue at the last uint of a storage buffer and reads it back into a
// second one (core/gl_test.cpp: buffers past the advertised
// GL_MAX_SHADER_STORAGE_BLOCK_SIZE).
layout(local_size_x = 1) in;
layout(std430, binding = 0) buffer Big { uint big[]; };
layout(std430, binding = 1) buffer Out { uint outValue[]; };
uniform uint uLast;
uniform uint uValue;
void main() {
  big[uLast] = uValue;
  memoryBarrierBuffer();
  outValue[0] = big[uLast];
  outValue[1] = uint(big.length());
}
