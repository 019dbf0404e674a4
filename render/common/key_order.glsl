// The order of fragment keys (depth bits, primitive id): see fragment_key.glsl.
bool keyLess(uvec2 a, uvec2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); }
