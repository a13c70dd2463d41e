// The negative control of src/glsl/family_shaders.h, compiled (never linked or run) by
// tests/gl/CMakeLists.txt: a lobe family or full BRDF in a variant without its shader overload
// does not compile; with SPECULA_WITH_SHADERS, which gives both their overloads, it does.
#include "src/glsl/family_shaders.h"

namespace specula::glsl {

struct NewLobe {};
struct NewBrdf {};

#ifdef SPECULA_WITH_SHADERS
constexpr LobeShader lobe_shader(const NewLobe&) { return {"lobes/new.glsl", "specula_new_lobe", ""}; }
constexpr std::string_view brdf_shader(const NewBrdf&) { return "brdfs/new.glsl"; }
#endif

#if defined(SPECULA_WITH_SHADERS) || defined(SPECULA_CHECK_LOBE)
LobeShader lobe_file(const std::variant<lobes::Power<double>, NewLobe>& lobe) { return lobe_shader_of(lobe); }
#endif
#if defined(SPECULA_WITH_SHADERS) || defined(SPECULA_CHECK_BRDF)
std::string_view brdf_file(const std::variant<Ggx, NewBrdf>& brdf) { return brdf_shader_of(brdf); }
#endif

}  // namespace specula::glsl
