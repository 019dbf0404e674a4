// The GL 4.5 entry points the GL backend uses, loaded at run time through the
// platform's getProcAddress (EGL or OSMesa), so no libGL is linked: linking
// libGL and libOSMesa into one process clashes on gl* symbols.
#pragma once

#include <GL/glcorearb.h>

#define SB_GL_FUNCTIONS(X)                                               \
  X(PFNGLGETSTRINGPROC, GetString)                                       \
  X(PFNGLGETSTRINGIPROC, GetStringi)                                     \
  X(PFNGLGETINTEGERVPROC, GetIntegerv)                                   \
  X(PFNGLGETINTEGER64VPROC, GetInteger64v)                               \
  X(PFNGLGETERRORPROC, GetError)                                         \
  X(PFNGLENABLEPROC, Enable)                                             \
  X(PFNGLDISABLEPROC, Disable)                                           \
  X(PFNGLENABLEIPROC, Enablei)                                           \
  X(PFNGLDISABLEIPROC, Disablei)                                         \
  X(PFNGLCLIPCONTROLPROC, ClipControl)                                   \
  X(PFNGLCREATEBUFFERSPROC, CreateBuffers)                               \
  X(PFNGLNAMEDBUFFERSTORAGEPROC, NamedBufferStorage)                     \
  X(PFNGLNAMEDBUFFERSUBDATAPROC, NamedBufferSubData)                     \
  X(PFNGLCLEARNAMEDBUFFERDATAPROC, ClearNamedBufferData)                 \
  X(PFNGLCLEARTEXIMAGEPROC, ClearTexImage)                               \
  X(PFNGLGETNAMEDBUFFERSUBDATAPROC, GetNamedBufferSubData)               \
  X(PFNGLDELETEBUFFERSPROC, DeleteBuffers)                               \
  X(PFNGLBINDBUFFERBASEPROC, BindBufferBase)                             \
  X(PFNGLCREATETEXTURESPROC, CreateTextures)                             \
  X(PFNGLTEXTURESTORAGE2DPROC, TextureStorage2D)                         \
  X(PFNGLTEXTURESTORAGE3DPROC, TextureStorage3D)                         \
  X(PFNGLGENTEXTURESPROC, GenTextures)                                   \
  X(PFNGLTEXTUREVIEWPROC, TextureView)                                   \
  X(PFNGLTEXTUREPARAMETERIPROC, TextureParameteri)                       \
  X(PFNGLDELETETEXTURESPROC, DeleteTextures)                             \
  X(PFNGLBINDTEXTUREUNITPROC, BindTextureUnit)                           \
  X(PFNGLGETTEXTUREIMAGEPROC, GetTextureImage)                           \
  X(PFNGLCREATEFRAMEBUFFERSPROC, CreateFramebuffers)                     \
  X(PFNGLNAMEDFRAMEBUFFERTEXTUREPROC, NamedFramebufferTexture)           \
  X(PFNGLNAMEDFRAMEBUFFERTEXTURELAYERPROC, NamedFramebufferTextureLayer) \
  X(PFNGLNAMEDFRAMEBUFFERDRAWBUFFERSPROC, NamedFramebufferDrawBuffers)   \
  X(PFNGLCHECKNAMEDFRAMEBUFFERSTATUSPROC, CheckNamedFramebufferStatus)   \
  X(PFNGLNAMEDFRAMEBUFFERPARAMETERIPROC, NamedFramebufferParameteri)     \
  X(PFNGLDELETEFRAMEBUFFERSPROC, DeleteFramebuffers)                     \
  X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer)                           \
  X(PFNGLCLEARNAMEDFRAMEBUFFERFVPROC, ClearNamedFramebufferfv)           \
  X(PFNGLCLEARNAMEDFRAMEBUFFERUIVPROC, ClearNamedFramebufferuiv)         \
  X(PFNGLVIEWPORTPROC, Viewport)                                         \
  X(PFNGLCREATESHADERPROC, CreateShader)                                 \
  X(PFNGLSHADERSOURCEPROC, ShaderSource)                                 \
  X(PFNGLCOMPILESHADERPROC, CompileShader)                               \
  X(PFNGLGETSHADERIVPROC, GetShaderiv)                                   \
  X(PFNGLGETSHADERINFOLOGPROC, GetShaderInfoLog)                         \
  X(PFNGLCREATEPROGRAMPROC, CreateProgram)                               \
  X(PFNGLATTACHSHADERPROC, AttachShader)                                 \
  X(PFNGLLINKPROGRAMPROC, LinkProgram)                                   \
  X(PFNGLGETPROGRAMIVPROC, GetProgramiv)                                 \
  X(PFNGLGETPROGRAMINFOLOGPROC, GetProgramInfoLog)                       \
  X(PFNGLDELETESHADERPROC, DeleteShader)                                 \
  X(PFNGLDELETEPROGRAMPROC, DeleteProgram)                               \
  X(PFNGLUSEPROGRAMPROC, UseProgram)                                     \
  X(PFNGLCREATEVERTEXARRAYSPROC, CreateVertexArrays)                     \
  X(PFNGLDELETEVERTEXARRAYSPROC, DeleteVertexArrays)                     \
  X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray)                           \
  X(PFNGLDRAWARRAYSINSTANCEDPROC, DrawArraysInstanced)                   \
  X(PFNGLDISPATCHCOMPUTEPROC, DispatchCompute)                           \
  X(PFNGLMEMORYBARRIERPROC, MemoryBarrier)                               \
  X(PFNGLFINISHPROC, Finish)                                             \
  X(PFNGLCREATEQUERIESPROC, CreateQueries)                               \
  X(PFNGLDELETEQUERIESPROC, DeleteQueries)                               \
  X(PFNGLQUERYCOUNTERPROC, QueryCounter)                                 \
  X(PFNGLGENQUERIESPROC, GenQueries)                                     \
  X(PFNGLBEGINQUERYPROC, BeginQuery)                                     \
  X(PFNGLENDQUERYPROC, EndQuery)                                         \
  X(PFNGLGETQUERYOBJECTUI64VPROC, GetQueryObjectui64v)                   \
  X(PFNGLDEPTHMASKPROC, DepthMask)                                       \
  X(PFNGLDEPTHFUNCPROC, DepthFunc)                                       \
  X(PFNGLBLENDFUNCSEPARATEIPROC, BlendFuncSeparatei)                     \
  X(PFNGLBLENDEQUATIONSEPARATEIPROC, BlendEquationSeparatei)             \
  X(PFNGLLOGICOPPROC, LogicOp)                                           \
  X(PFNGLCOLORMASKIPROC, ColorMaski)                                     \
  X(PFNGLLINEWIDTHPROC, LineWidth)                                       \
  X(PFNGLPIXELSTOREIPROC, PixelStorei)                                   \
  X(PFNGLBLITNAMEDFRAMEBUFFERPROC, BlitNamedFramebuffer)                 \
  X(PFNGLNAMEDFRAMEBUFFERREADBUFFERPROC, NamedFramebufferReadBuffer)     \
  X(PFNGLREADPIXELSPROC, ReadPixels)                                     \
  X(PFNGLTEXTURESUBIMAGE3DPROC, TextureSubImage3D)                       \
  X(PFNGLTEXTURESUBIMAGE2DPROC, TextureSubImage2D)                       \
  X(PFNGLTEXTURESTORAGE2DMULTISAMPLEPROC, TextureStorage2DMultisample)   \
  X(PFNGLGETINTERNALFORMATIVPROC, GetInternalformativ)

namespace sb {

struct GLFunctions {
#define SB_GL_DECLARE(type, name) type name = nullptr;
  SB_GL_FUNCTIONS(SB_GL_DECLARE)
#undef SB_GL_DECLARE
};

}  // namespace sb
