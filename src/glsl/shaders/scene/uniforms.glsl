// The scene shader's inputs: render/scene.h's scene as uniforms and two float textures (gl/scene_shader.h, SceneUniforms and MeshTextures).
// SCENE_MESH 0 leaves the triangle traversal out: for scenes of spheres alone. (llvmpipe runs
// code under a branch not taken with its lanes masked off: the unused traversal would cost it 4x.)
#ifndef SCENE_MESH
#define SCENE_MESH ${mesh}
#endif
const int SCENE_MAX_SPHERES = ${max_spheres};
const int SCENE_MAX_LIGHTS = ${max_lights};
const int SCENE_BVH_STACK = ${bvh_stack};
const float SCENE_FAR = 3.0e38;
const float SCENE_INV_PI = 0.318309886;

uniform vec2 u_resolution;
uniform vec2 u_pixel_offset;
uniform vec3 u_eye;
uniform vec3 u_forward;
uniform vec3 u_right;
uniform vec3 u_up;
uniform int u_sphere_count;
uniform vec4 u_spheres[SCENE_MAX_SPHERES];
uniform int u_light_count;
uniform vec4 u_lights[SCENE_MAX_LIGHTS];
uniform vec3 u_light_irradiance[SCENE_MAX_LIGHTS];
uniform vec3 u_diffuse;
uniform vec3 u_specular;
uniform vec3 u_ambient;
uniform vec3 u_background;
uniform vec4 u_model_params;
uniform int u_triangle_count;
uniform highp sampler2D u_triangles;
uniform highp sampler2D u_bvh;
uniform int u_display;
uniform float u_exposure;
uniform int u_tone_map;

out vec4 scene_colour;
