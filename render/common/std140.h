// The C++ side of render/common/uniform_block.h: a uniform block is a struct
// of glm types in namespace sb, and a static_assert checks at compile time that
// each member's offset and the struct's size are the std140 ones, so that the
// bytes the C++ uploads are where the shader reads them.
//
// The members are chained by __COUNTER__: SB_UNIFORM_BLOCK declares link c, each
// field link c + 1, c + 2, ..., and each link computes the std140 offset of its
// member from the end of the link before it. The functions are member function
// bodies, where the struct is complete (offsetof, sizeof).
#pragma once

#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>

namespace sb::std140 {

// The std140 rules (OpenGL 4.6, 7.6.2.2) of one GLSL type.
struct Rule {
  std::size_t align, size;
};
template <class T>
struct RuleOf;
template <>
struct RuleOf<float> {
  static constexpr Rule rule{4, 4};
};
template <>
struct RuleOf<int32_t> {
  static constexpr Rule rule{4, 4};
};
template <>
struct RuleOf<uint32_t> {
  static constexpr Rule rule{4, 4};
};
template <int N, class T>
struct RuleOf<glm::vec<N, T, glm::defaultp>> {
  static_assert(sizeof(T) == 4);
  static constexpr Rule rule{N == 2 ? 8u : 16u, N * 4u};  // vec3 aligns as vec4, is 12 bytes
};
template <>
struct RuleOf<glm::mat4> {
  static constexpr Rule rule{16, 64};  // column-major: an array of 4 vec4
};

constexpr std::size_t alignUp(std::size_t x, std::size_t a) { return (x + a - 1) / a * a; }

// A member of rule r (count elements; 0: not an array) after `end`: its offset,
// and the end of what it occupies. An array's elements align and step as vec4s
// at least (rule 4).
constexpr std::size_t offsetAfter(std::size_t end, Rule r, std::size_t count) {
  return alignUp(end, count ? alignUp(r.align, 16) : r.align);
}
constexpr std::size_t memberEnd(std::size_t end, Rule r, std::size_t count) {
  return offsetAfter(end, r, count) + (count ? count * alignUp(r.size, 16) : r.size);
}
// The size of a block whose last member ends at `end`: rounded up to a vec4 (rule 9).
constexpr std::size_t blockSize(std::size_t end) { return alignUp(end, 16); }

// The state of the chain after a member: where std140 ends it, and the first
// member the C++ places elsewhere (nullptr while none).
struct Check {
  std::size_t end = 0;
  const char* mismatch = nullptr;
};
constexpr Check next(Check before, Rule r, std::size_t count, std::size_t cppOffset,
                     const char* name) {
  const std::size_t at = offsetAfter(before.end, r, count);
  return {memberEnd(before.end, r, count),
          before.mismatch ? before.mismatch : (cppOffset == at ? nullptr : name)};
}
constexpr const char* finish(Check last, std::size_t cppSize) {
  return last.mismatch ? last.mismatch : (cppSize == blockSize(last.end) ? nullptr : "sizeof");
}

template <int>
struct Link {};

}  // namespace sb::std140

// The C++ type of a GLSL type name.
#define SB_T_float float
#define SB_T_int int32_t
#define SB_T_uint uint32_t
#define SB_T_vec2 glm::vec2
#define SB_T_vec3 glm::vec3
#define SB_T_vec4 glm::vec4
#define SB_T_ivec2 glm::ivec2
#define SB_T_ivec3 glm::ivec3
#define SB_T_ivec4 glm::ivec4
#define SB_T_uvec2 glm::uvec2
#define SB_T_uvec3 glm::uvec3
#define SB_T_uvec4 glm::uvec4
#define SB_T_mat4 glm::mat4

// clang-format off
#define SB_UNIFORM_BLOCK(Name, slot) SB_UNIFORM_BLOCK_AT_(Name, slot, __COUNTER__)
#define SB_UNIFORM_BLOCK_AT_(Name, slot, c)                                      \
  namespace sb {                                                                 \
  struct Name {                                                                  \
    static constexpr uint32_t kBinding = slot;                                   \
    using SbBlock_ = Name;                                                       \
    static constexpr ::sb::std140::Check sbLink_(::sb::std140::Link<c>) { return {}; }

#define SB_FIELD(type, name) SB_MEMBER_(type, name, , 0, __COUNTER__)
#define SB_ARRAY(type, name, count) SB_MEMBER_(type, name, [count], count, __COUNTER__)
#define SB_MEMBER_(type, name, dims, count, c)                                          \
  SB_T_##type name dims;                                                                \
  static constexpr ::sb::std140::Check sbLink_(::sb::std140::Link<c>) {                 \
    return ::sb::std140::next(sbLink_(::sb::std140::Link<c - 1>{}),                     \
                              ::sb::std140::RuleOf<SB_T_##type>::rule, count,           \
                              offsetof(SbBlock_, name), #name);                         \
  }

// std140Mismatch(): nullptr when the C++ layout is the std140 one, else the first
// member the C++ places elsewhere ("sizeof": the size differs).
#define SB_UNIFORM_BLOCK_END_UNCHECKED(Name)                                        \
  static constexpr const char* std140Mismatch() {                                   \
    return ::sb::std140::finish(sbLink_(::sb::std140::Link<__COUNTER__ - 1>{}),     \
                                sizeof(SbBlock_));                                  \
  }                                                                                 \
  };                                                                                \
  }
#define SB_UNIFORM_BLOCK_END(Name)     \
  SB_UNIFORM_BLOCK_END_UNCHECKED(Name) \
  static_assert(::sb::Name::std140Mismatch() == nullptr, #Name " is not laid out as std140");
// clang-format on
