#include "telear/render/shaders.hpp"

namespace telear::render::shaders {

// The array size must equal MeshSetRenderer::kMaxParts.
const char* const kSurfaceVertex = R"glsl(#version 330 core
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec3 a_colour;
layout(std140) uniform Parts { mat4 T_base_part[64]; };
uniform mat4 u_projection;
uniform mat4 u_T_view_base;
uniform int u_part;
uniform bool u_lit;
uniform vec3 u_light_dir_view;
uniform vec3 u_ambient;
uniform vec3 u_diffuse;
uniform bool u_use_colour;
uniform vec3 u_colour;
out vec3 v_colour;
void main() {
  mat4 T_view_part = u_T_view_base * T_base_part[u_part];
  vec4 p_view = T_view_part * vec4(a_position, 1.0);
  vec3 c = u_use_colour ? u_colour : a_colour;
  if (u_lit) {
    // Rigid transforms: the normal needs no inverse-transpose. Lit on the side facing the
    // camera (at the view-frame origin), so open shapes and inside faces shade sensibly.
    vec3 n = normalize(mat3(T_view_part) * a_normal);
    if (dot(n, p_view.xyz) > 0.0) n = -n;
    c *= u_ambient + u_diffuse * max(dot(n, u_light_dir_view), 0.0);
  }
  v_colour = min(c, vec3(1.0));
  gl_Position = u_projection * p_view;
}
)glsl";

const char* const kSurfaceFragment = R"glsl(#version 330 core
in vec3 v_colour;
uniform float u_alpha;
out vec4 frag_colour;
void main() { frag_colour = vec4(v_colour, u_alpha); }
)glsl";

const char* const kBackgroundVertex = R"glsl(#version 330 core
out vec2 v_uv;
void main() {
  // A quad over the viewport as a 4-vertex strip from gl_VertexID.
  vec2 p = vec2(float(gl_VertexID & 1), float((gl_VertexID >> 1) & 1));
  v_uv = p;
  gl_Position = vec4(2.0 * p - 1.0, 0.0, 1.0);
}
)glsl";

const char* const kBackgroundFragment = R"glsl(#version 330 core
in vec2 v_uv;
uniform sampler2D u_frame;
out vec4 frag_colour;
void main() { frag_colour = texture(u_frame, v_uv); }
)glsl";

const char* const kYCbCrFragment = R"glsl(#version 330 core
in vec2 v_uv;
uniform sampler2D u_y;
uniform sampler2D u_cb;
uniform sampler2D u_cr;
// The chroma planes' coordinate of a luma coordinate: 1 for even sizes; an odd size's last
// chroma pixel also covers the padding, so the plane spans a little more than the image.
uniform vec2 u_chroma_scale;
out vec4 frag_colour;
void main() {
  vec2 uv = vec2(v_uv.x, 1.0 - v_uv.y);
  vec2 chroma_uv = uv * u_chroma_scale;
  // Luma at the pixel itself: a fetch, no filtering (the target is the luma's size).
  ivec2 size = textureSize(u_y, 0);
  float y = texelFetch(u_y, ivec2(gl_FragCoord.x, float(size.y) - gl_FragCoord.y), 0).r * 255.0;
  float cb = texture(u_cb, chroma_uv).r * 255.0 - 128.0;
  float cr = texture(u_cr, chroma_uv).r * 255.0 - 128.0;
  vec3 rgb = vec3(y + 1.402 * cr, y - 0.344136 * cb - 0.714136 * cr, y + 1.772 * cb);
  frag_colour = vec4(clamp(rgb / 255.0, 0.0, 1.0), 1.0);
}
)glsl";

}  // namespace telear::render::shaders
