// No shadows: the light is always fully visible.
float shadowVisibility(vec3 worldPos) { return 1.0; }
