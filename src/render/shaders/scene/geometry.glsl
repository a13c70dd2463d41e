// Ray casting for the scene shader, as render/render.cpp and render/bvh.cpp cast rays on the CPU: Haines et al. 2019 (spheres), Moller & Trumbore 1997 (triangles), Kay & Kajiya 1986 (BVH boxes), Wachter & Binder 2019 (ray offsets).
// Needs scene/uniforms.glsl before it.
// Haines et al. 2019, "Precision Improvements for Ray/Sphere Intersection" (Ray Tracing Gems, ch. 7): discriminant from |f - (f.d)d|^2, far root from the product of the roots. Nearest t in (t_min, t_max), or -1.
float scene_sphere_hit(vec3 origin, vec3 direction, vec4 sphere, float t_min, float t_max) {
  vec3 f = origin - sphere.xyz;
  float b = -dot(f, direction);
  vec3 chord = f + b * direction;
  float r2 = sphere.w * sphere.w;
  float discriminant = r2 - dot(chord, chord);
  if (discriminant < 0.0) return -1.0;
  float q = b + (b < 0.0 ? -1.0 : 1.0) * sqrt(discriminant);
  float t0 = (dot(f, f) - r2) / q;
  float near_t = min(t0, q), far_t = max(t0, q);
  if (near_t > t_min && near_t < t_max) return near_t;
  if (far_t > t_min && far_t < t_max) return far_t;
  return -1.0;
}

// The i-th RGBA32F texel of a texture read as a flat array, row-major.
vec4 scene_texel(highp sampler2D data, int i) {
  int width = textureSize(data, 0).x;
  return texelFetch(data, ivec2(i % width, i / width), 0);
}

// Moller & Trumbore 1997, "Fast, Minimum Storage Ray/Triangle Intersection" (render/bvh.cpp): (t, u, v) of a hit with t_min < t < t_max, both faces; t = -1 if none.
vec3 scene_triangle_hit(vec3 origin, vec3 direction, int triangle, float t_min, float t_max) {
  vec3 v0 = scene_texel(u_triangles, 6 * triangle).xyz;
  vec3 e1 = scene_texel(u_triangles, 6 * triangle + 1).xyz;
  vec3 e2 = scene_texel(u_triangles, 6 * triangle + 2).xyz;
  vec3 p = cross(direction, e2);
  float det = dot(e1, p);
  if (det == 0.0) return vec3(-1.0);
  float inv_det = 1.0 / det;
  vec3 s = origin - v0;
  float u = dot(s, p) * inv_det;
  if (!(u >= 0.0 && u <= 1.0)) return vec3(-1.0);
  vec3 q = cross(s, e1);
  float v = dot(direction, q) * inv_det;
  if (!(v >= 0.0 && u + v <= 1.0)) return vec3(-1.0);
  float t = dot(e2, q) * inv_det;
  return t > t_min && t < t_max ? vec3(t, u, v) : vec3(-1.0);
}

// Kay & Kajiya 1986 slab test (render/bvh.cpp); the exit distance widened by 1 + 2 gamma_3 as in Pharr, Jakob & Humphreys, PBR 3rd ed., 3.9.2, so float rounding never drops a box the double test keeps. Entry t within (t_min, t_max), or SCENE_FAR.
float scene_box_entry(int node, vec3 origin, vec3 inverse, float t_min, float t_max) {
  vec3 lo = scene_texel(u_bvh, 2 * node).xyz;
  vec3 hi = scene_texel(u_bvh, 2 * node + 1).xyz;
  vec3 a = (lo - origin) * inverse, b = (hi - origin) * inverse;
  vec3 near_t = min(a, b), far_t = max(a, b) * 1.0000004;
  float enter = max(t_min, max(near_t.x, max(near_t.y, near_t.z)));
  float leave = min(t_max, min(far_t.x, min(far_t.y, far_t.z)));
  return enter <= leave ? enter : SCENE_FAR;
}

// 1/d per axis, a zero component replaced by a tiny one of the same sign so that no slab gives 0 * inf = NaN (render/bvh.cpp lets a NaN slab constrain nothing; this keeps the same boxes).
vec3 scene_inverse_direction(vec3 d) {
  vec3 tiny = mix(vec3(1e-30), vec3(-1e-30), lessThan(d, vec3(0.0)));
  return 1.0 / mix(d, tiny, lessThan(abs(d), vec3(1e-30)));
}

// render/bvh.cpp's traversal: a stack of (node, entry t), nearer child popped first. Returns the nearest hit (t, u, v) with t_min < t < t_max (any hit if any_hit) and its triangle, or t = -1.
vec3 scene_mesh_hit(vec3 origin, vec3 direction, float t_min, float t_max, bool any_hit, out int triangle) {
  triangle = -1;
  vec3 best = vec3(-1.0);
  if (u_triangle_count == 0) return best;
  vec3 inverse = scene_inverse_direction(direction);
  int nodes[SCENE_BVH_STACK];
  float entries[SCENE_BVH_STACK];
  int top = 1;
  nodes[0] = 0;
  entries[0] = scene_box_entry(0, origin, inverse, t_min, t_max);
  while (top > 0) {
    --top;
    int node = nodes[top];
    if (!(entries[top] < t_max)) continue;
    vec4 lo = scene_texel(u_bvh, 2 * node), hi = scene_texel(u_bvh, 2 * node + 1);
    int count = int(hi.w);
    if (count > 0) {
      for (int i = int(lo.w); i < int(lo.w) + count; ++i) {
        vec3 hit = scene_triangle_hit(origin, direction, i, t_min, t_max);
        if (hit.x < 0.0) continue;
        t_max = hit.x;
        best = hit;
        triangle = i;
        if (any_hit) return best;
      }
      continue;
    }
    int near_node = node + 1, far_node = int(lo.w);
    float near_t = scene_box_entry(near_node, origin, inverse, t_min, t_max);
    float far_t = scene_box_entry(far_node, origin, inverse, t_min, t_max);
    if (far_t < near_t) {
      int n = near_node; near_node = far_node; far_node = n;
      float t = near_t; near_t = far_t; far_t = t;
    }
    nodes[top] = far_node; entries[top] = far_t; ++top;
    nodes[top] = near_node; entries[top] = near_t; ++top;
  }
  return best;
}

struct SceneSurface {
  vec3 point;
  vec3 normal;     // shading normal, unit, on the viewer's side
  vec3 geometric;  // face normal, unit, on the viewer's side
};

// render.cpp, Geometry::facing_viewer: surfaces are two-sided, both normals turned toward the viewer.
SceneSurface scene_facing_viewer(vec3 point, vec3 direction, vec3 normal, vec3 geometric) {
  if (dot(geometric, direction) > 0.0) geometric = -geometric;
  if (dot(normal, geometric) < 0.0) normal = -normal;
  return SceneSurface(point, normal, geometric);
}

// render.cpp, Geometry::triangle_surface: the face normal, or the vertex normals interpolated at (u, v) where the triangle has them.
SceneSurface scene_triangle_surface(vec3 origin, vec3 direction, int triangle, vec3 hit) {
  vec4 v0 = scene_texel(u_triangles, 6 * triangle);
  vec3 face = normalize(cross(scene_texel(u_triangles, 6 * triangle + 1).xyz, scene_texel(u_triangles, 6 * triangle + 2).xyz));
  vec3 smooth_normal = scene_texel(u_triangles, 6 * triangle + 3).xyz * (1.0 - hit.y - hit.z) +
                       scene_texel(u_triangles, 6 * triangle + 4).xyz * hit.y +
                       scene_texel(u_triangles, 6 * triangle + 5).xyz * hit.z;
  bool use_smooth = v0.w > 0.5 && length(smooth_normal) > 0.0;
  return scene_facing_viewer(origin + direction * hit.x, direction, use_smooth ? normalize(smooth_normal) : face, face);
}

// render.cpp, Geometry::closest: the nearest sphere, then the mesh closer than it. False if the ray hits nothing.
bool scene_closest(vec3 origin, vec3 direction, out SceneSurface surface) {
  float t_max = SCENE_FAR;
  int sphere = -1;
  for (int i = 0; i < u_sphere_count; ++i) {
    float t = scene_sphere_hit(origin, direction, u_spheres[i], 0.0, t_max);
    if (t < 0.0) continue;
    t_max = t;
    sphere = i;
  }
#if SCENE_MESH
  int triangle;
  vec3 hit = scene_mesh_hit(origin, direction, 0.0, t_max, false, triangle);
  if (triangle >= 0) {
    surface = scene_triangle_surface(origin, direction, triangle, hit);
    return true;
  }
#endif
  if (sphere < 0) return false;
  vec3 point = origin + direction * t_max;
  vec3 n = (point - u_spheres[sphere].xyz) / u_spheres[sphere].w;
  surface = scene_facing_viewer(point, direction, n, n);
  return true;
}

// render.cpp, Geometry::occluded: any sphere or triangle with 0 < t < t_max.
bool scene_occluded(vec3 origin, vec3 direction, float t_max) {
  for (int i = 0; i < u_sphere_count; ++i)
    if (scene_sphere_hit(origin, direction, u_spheres[i], 0.0, t_max) >= 0.0) return true;
#if SCENE_MESH
  int triangle;
  scene_mesh_hit(origin, direction, 0.0, t_max, true, triangle);
  return triangle >= 0;
#else
  return false;
#endif
}

// Wachter & Binder 2019, "A Fast and Robust Method for Avoiding Self-Intersection" (Ray Tracing Gems, ch. 6): p moved off its surface along n by a few float ulps (a fixed distance near the origin). The CPU's 1e-9 |p| offset is below float resolution.
vec3 scene_offset_ray(vec3 p, vec3 n) {
  ivec3 ulps = ivec3(256.0 * n) * (ivec3(1) - 2 * ivec3(lessThan(p, vec3(0.0))));
  vec3 moved = intBitsToFloat(floatBitsToInt(p) + ulps);
  return mix(moved, p + n / 65536.0, lessThan(abs(p), vec3(1.0 / 32.0)));
}
