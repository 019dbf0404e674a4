// marschner in the hair shading passes (bound as <shading>, render/shading/hair_shading.glsl):
// shadingDirect is the light's term for a light of unit colour; the light's visibility
// multiplies it (hair_shading.glsl), left as it is.
#include "uniforms.h"
#include "marschner.glsl"

vec3 shadingDirect(vec3 T, vec3 L, vec3 V, vec3 color, inout float visibility) {
  // A Kajiya-Kay diffuse term beside the scattering function (the thesis, Listing 2, line 3).
  float tl = dot(T, L);
  float diffuse = sqrt(max(0.0f, 1.0f - tl * tl));
  // L_r = D * integral of S L_i cos(theta_i): one light, cos(theta_i) = sin(T, L).
  vec3 specular = marschner(T, L, V, color, vec4(marschnerAlpha.xyz, marschnerEta),
                            vec4(marschnerBeta.xyz, marschnerCaustic)) *
                  diffuse;
  return marschnerDiffuse * diffuse * color + marschnerSpecular * specular;
}
