// GLSL ES 3.00 of the page, as RawShaderMaterials: three.js adds only `#version 300 es` and
// a few #defines, no colour-space conversion or tone mapping, so a colour reaches the
// framebuffer as the native renderer (src/render/shaders.cpp, overlay.cpp) writes it.
//
// Pixel conventions (render/camera_projection.hpp): OpenCV pixel (u, v) has its centre at
// integer coordinates, row 0 at the top; a GL framebuffer's row 0 is at the bottom. The
// full-screen passes work from v_uv in [0, 1] over the viewport rather than gl_FragCoord, so
// the same pass fills an eye's canvas (viewport = image: v_uv hits pixel centres exactly) and
// an XR view's viewport of any size:
//     u = v_uv.x * W - 0.5,   v = (1 - v_uv.y) * H - 0.5.

import * as THREE from 'three';

// The arm and the scene objects, lit per vertex exactly as the native surface shader:
//   rgb = c * (ambient + diffuse * max(dot(n, l), 0)), n flipped towards the camera.
// The part's placement comes from modelViewMatrix = view * T_base_part (three.js computes it
// in double precision from the camera's matrixWorldInverse and the mesh's matrixWorld).
const kSurfaceVertex = `
precision highp float;
uniform mat4 modelViewMatrix;
uniform mat4 projectionMatrix;
uniform mat4 viewMatrix;
uniform bool u_lit;
uniform vec3 u_light_dir_base;
uniform vec3 u_ambient;
uniform vec3 u_diffuse;
uniform bool u_use_colour;
uniform vec3 u_colour;
in vec3 position;
in vec3 normal;
in vec3 a_colour;
out vec3 v_colour;
void main() {
  vec4 p_view = modelViewMatrix * vec4(position, 1.0);
  vec3 c = u_use_colour ? u_colour : a_colour;
  if (u_lit) {
    // Rigid transforms: no inverse-transpose. Lit on the side facing the camera, so inside
    // faces and open shapes shade sensibly (the native shader's rule).
    vec3 n = normalize(mat3(modelViewMatrix) * normal);
    if (dot(n, p_view.xyz) > 0.0) n = -n;
    vec3 l = normalize(mat3(viewMatrix) * u_light_dir_base);
    c *= u_ambient + u_diffuse * max(dot(n, l), 0.0);
  }
  v_colour = min(c, vec3(1.0));
  gl_Position = projectionMatrix * p_view;
}
`;

const kSurfaceFragment = `
precision highp float;
uniform float u_alpha;
in vec3 v_colour;
out vec4 frag_colour;
void main() { frag_colour = vec4(v_colour, u_alpha); }
`;

// One triangle over the viewport: (-1,-1), (3,-1), (-1,3).
const kFullScreenVertex = `
precision highp float;
in vec3 position;
out vec2 v_uv;
void main() {
  v_uv = position.xy * 0.5 + 0.5;
  gl_Position = vec4(position.xy, 0.0, 1.0);
}
`;

// The raw video frame. Its texture holds the decoded JPEG with the image's row 0 in texel row
// 0 (an ImageBitmap is uploaded as decoded: WebGL's UNPACK_FLIP_Y does not apply to it, and
// the texture says flipY = false so three.js asks for none), so raw pixel (u, v) is texture
// coordinate ((u + 0.5) / W, (v + 0.5) / H) = (v_uv.x, 1 - v_uv.y): exactly a texel centre
// when the viewport is the image, which even bilinear filtering returns unchanged.
const kVideoFragment = `
precision highp float;
uniform sampler2D u_frame;
in vec2 v_uv;
out vec4 frag_colour;
void main() {
  frag_colour = vec4(texture(u_frame, vec2(v_uv.x, 1.0 - v_uv.y)).rgb, 1.0);
}
`;

// The ghost's pinhole image warped into the raw (distorted) image, premultiplied alpha over
// what is drawn (the native overlay's kWarpFragment). For raw pixel (u, v) the look-up table
// (RG32F, W x H, texel row 0 = the image's top row) gives q, the pinhole position of the same
// ray on the camera's plane; the region target shows that plane from pixel (x0, y0) on, with
// GL's bottom-up rows, so q - origin is texture coordinate
//     s = (q.x - x0 + 0.5) / region.x,   t = 1 - (q.y - y0 + 0.5) / region.y.
// Without a table yet (it follows the cameras message) the lens is taken as ideal: q = (u, v).
const kCompositeFragment = `
precision highp float;
uniform sampler2D u_scene;
uniform highp sampler2D u_lut;
uniform bool u_has_lut;
uniform vec2 u_image;
uniform vec2 u_origin;
uniform vec2 u_region;
in vec2 v_uv;
out vec4 frag_colour;
void main() {
  vec2 raw = vec2(v_uv.x * u_image.x - 0.5, (1.0 - v_uv.y) * u_image.y - 0.5);
  vec2 q = raw;
  if (u_has_lut) {
    ivec2 p = clamp(ivec2(floor(raw + 0.5)), ivec2(0), ivec2(u_image) - 1);
    q = texelFetch(u_lut, p, 0).rg;
  }
  q -= u_origin;
  if (q.x < -0.5 || q.y < -0.5 || q.x > u_region.x - 0.5 || q.y > u_region.y - 0.5) discard;
  frag_colour = texture(u_scene, vec2((q.x + 0.5) / u_region.x, 1.0 - (q.y + 0.5) / u_region.y));
}
`;

// The seed's lighting (render/draw_options.hpp): a directional light above, in front and to
// one side, in the base frame.
const kLightDirectionBase = new THREE.Vector3(0.4, -0.3, 1.0).normalize();
export const kHighlightColour = new THREE.Color(0.95, 0.08, 0.08);

export function surfaceMaterial({lit = true, colour = null, alpha = 1.0} = {}) {
  return new THREE.RawShaderMaterial({
    glslVersion: THREE.GLSL3,
    vertexShader: kSurfaceVertex,
    fragmentShader: kSurfaceFragment,
    uniforms: {
      u_lit: {value: lit},
      u_light_dir_base: {value: kLightDirectionBase},
      u_ambient: {value: new THREE.Vector3(0.35, 0.35, 0.35)},
      u_diffuse: {value: new THREE.Vector3(0.75, 0.75, 0.75)},
      u_use_colour: {value: colour !== null},
      u_colour: {value: colour !== null ? colour.clone() : new THREE.Color(1, 1, 1)},
      u_alpha: {value: alpha},
    },
    // Winding depends on the projection's handedness (y down); draw both sides.
    side: THREE.DoubleSide,
  });
}

const fullScreenTriangle = (() => {
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.Float32BufferAttribute([-1, -1, 0, 3, -1, 0, -1, 3, 0], 3));
  return geometry;
})();

function fullScreenMesh(material) {
  const mesh = new THREE.Mesh(fullScreenTriangle, material);
  mesh.frustumCulled = false;
  return mesh;
}

export function videoBackgroundMesh(texture) {
  const material = new THREE.RawShaderMaterial({
    glslVersion: THREE.GLSL3,
    vertexShader: kFullScreenVertex,
    fragmentShader: kVideoFragment,
    uniforms: {u_frame: {value: texture}},
    depthTest: false,
    depthWrite: false,
  });
  const mesh = fullScreenMesh(material);
  mesh.renderOrder = 0;
  return mesh;
}

export function compositeMesh() {
  const material = new THREE.RawShaderMaterial({
    glslVersion: THREE.GLSL3,
    vertexShader: kFullScreenVertex,
    fragmentShader: kCompositeFragment,
    uniforms: {
      u_scene: {value: null},
      u_lut: {value: null},
      u_has_lut: {value: false},
      u_image: {value: new THREE.Vector2(1, 1)},
      u_origin: {value: new THREE.Vector2(0, 0)},
      u_region: {value: new THREE.Vector2(1, 1)},
    },
    depthTest: false,
    depthWrite: false,
    // The region target holds premultiplied colour (the ghost blended over transparent black).
    transparent: true,
    blending: THREE.CustomBlending,
    blendEquation: THREE.AddEquation,
    blendSrc: THREE.OneFactor,
    blendDst: THREE.OneMinusSrcAlphaFactor,
    blendSrcAlpha: THREE.OneFactor,
    blendDstAlpha: THREE.OneMinusSrcAlphaFactor,
  });
  const mesh = fullScreenMesh(material);
  mesh.renderOrder = 1;
  return mesh;
}
