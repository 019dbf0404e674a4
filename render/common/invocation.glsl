// The linear index of a 1D compute invocation dispatched as a 2D grid of
// 64-wide groups (dispatchGroups() in technique.h): one dimension is capped at
// 65535 groups, i.e. 4.2M items, fewer than a 4096x4096 map has.
uint linearInvocation() {
  return gl_GlobalInvocationID.x + gl_GlobalInvocationID.y * gl_NumWorkGroups.x * 64u;
}
