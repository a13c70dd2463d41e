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

${uniforms}

out vec4 scene_colour;
