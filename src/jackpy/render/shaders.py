"""GLSL 330 core sources of the renderer's programs.

Lighting is done in view space: a headlight at the eye, a key light fixed in the world (so shapes
read the same while orbiting), a sky/ground hemisphere ambient, and a Blinn highlight for each.
Faces are lit on both sides, so open CAD meshes and the insides of volumes look right.
"""

MESH_VERTEX = """
#version 330 core
uniform mat4 u_view;
uniform mat4 u_proj;
in vec3 in_position;
in vec3 in_normal;
in vec3 in_vertex_color;
in mat4 in_model;
in mat3 in_normal_matrix;
in vec4 in_color;
in float in_highlight;
in int in_pick;
out vec3 v_position;
out vec3 v_normal;
out vec4 v_color;
out float v_highlight;
flat out int v_pick;
void main() {
    vec4 p = u_view * (in_model * vec4(in_position, 1.0));
    v_position = p.xyz;
    v_normal = mat3(u_view) * (in_normal_matrix * in_normal);
    v_color = vec4(in_color.rgb * in_vertex_color, in_color.a);
    v_highlight = in_highlight;
    v_pick = in_pick;
    gl_Position = u_proj * p;
}
"""

SKIN_VERTEX = """
#version 330 core
// Linear-blend skinning: four bones per vertex. u_bones holds six RGBA32F texels per bone (row =
// bone): the skinning matrix's four columns, the owned vertices' colour, then (pick id, highlight).
uniform mat4 u_view;
uniform mat4 u_proj;
uniform sampler2D u_bones;
in vec3 in_position;
in vec3 in_normal;
in ivec4 in_joints;
in vec4 in_weights;
in int in_owner;
out vec3 v_position;
out vec3 v_normal;
out vec4 v_color;
out float v_highlight;
flat out int v_pick;
mat4 bone(int b) {
    return mat4(texelFetch(u_bones, ivec2(0, b), 0), texelFetch(u_bones, ivec2(1, b), 0),
                texelFetch(u_bones, ivec2(2, b), 0), texelFetch(u_bones, ivec2(3, b), 0));
}
void main() {
    mat4 m = in_weights.x * bone(in_joints.x) + in_weights.y * bone(in_joints.y)
           + in_weights.z * bone(in_joints.z) + in_weights.w * bone(in_joints.w);
    vec4 p = u_view * (m * vec4(in_position, 1.0));
    v_position = p.xyz;
    v_normal = mat3(u_view) * (mat3(m) * in_normal);  // bones are rigid: the blend is near-orthogonal
    v_color = texelFetch(u_bones, ivec2(4, in_owner), 0);
    vec4 extra = texelFetch(u_bones, ivec2(5, in_owner), 0);
    v_highlight = extra.y;
    v_pick = int(extra.x + 0.5);
    gl_Position = u_proj * p;
}
"""

RIGID_VERTEX = """
#version 330 core
// Merged rigid items (jackpy.render.rigid): each vertex's item places it. u_bones holds six RGBA32F
// texels per item (row = item): the model matrix's four columns, the colour, then (pick id, highlight).
uniform mat4 u_view;
uniform mat4 u_proj;
uniform sampler2D u_bones;
in vec3 in_position;
in vec3 in_normal;
in int in_owner;
out vec3 v_position;
out vec3 v_normal;
out vec4 v_color;
out float v_highlight;
flat out int v_pick;
void main() {
    mat4 m = mat4(texelFetch(u_bones, ivec2(0, in_owner), 0), texelFetch(u_bones, ivec2(1, in_owner), 0),
                  texelFetch(u_bones, ivec2(2, in_owner), 0), texelFetch(u_bones, ivec2(3, in_owner), 0));
    vec4 p = u_view * (m * vec4(in_position, 1.0));
    v_position = p.xyz;
    v_normal = mat3(u_view) * (mat3(m) * in_normal);  // rigid: the rotation maps normals
    v_color = texelFetch(u_bones, ivec2(4, in_owner), 0);
    vec4 extra = texelFetch(u_bones, ivec2(5, in_owner), 0);
    v_highlight = extra.y;
    v_pick = int(extra.x + 0.5);
    gl_Position = u_proj * p;
}
"""

MESH_FRAGMENT = """
#version 330 core
uniform vec3 u_key_direction;   // towards the key light, view space, unit
uniform vec3 u_up;              // world up in view space
uniform bool u_orthographic;
uniform bool u_flat;            // wireframe overlay: unlit darkened colour
uniform vec3 u_highlight_color;
in vec3 v_position;
in vec3 v_normal;
in vec4 v_color;
in float v_highlight;
out vec4 f_color;
void main() {
    if (u_flat) {
        vec3 edge = mix(v_color.rgb * 0.3, u_highlight_color, 0.6 * v_highlight);
        f_color = vec4(edge, max(v_color.a, 0.5));
        return;
    }
    vec3 v = u_orthographic ? vec3(0.0, 0.0, 1.0) : normalize(-v_position);
    vec3 n = normalize(v_normal);
    if (dot(n, v) < 0.0) n = -n;
    float head = max(dot(n, v), 0.0);
    float key = max(dot(n, u_key_direction), 0.0);
    vec3 ambient = mix(vec3(0.20, 0.19, 0.18), vec3(0.34, 0.36, 0.40), 0.5 + 0.5 * dot(n, u_up));
    float spec = 0.25 * pow(max(dot(n, normalize(u_key_direction + v)), 0.0), 40.0) * step(0.0, key)
               + 0.12 * pow(head, 60.0);
    vec3 color = v_color.rgb * (ambient + 0.45 * head + 0.55 * key) + vec3(spec);
    float rim = pow(1.0 - head, 2.0);
    color = mix(color, u_highlight_color, 0.25 * v_highlight) + u_highlight_color * rim * 0.9 * v_highlight;
    f_color = vec4(color, v_color.a);
}
"""

PICK_FRAGMENT = """
#version 330 core
flat in int v_pick;
out int f_pick;
void main() {
    f_pick = v_pick;
}
"""

LINE_VERTEX = """
#version 330 core
uniform mat4 u_view;
uniform mat4 u_proj;
in vec3 in_position;
in vec4 in_color;
out vec4 v_color;
void main() {
    v_color = in_color;
    gl_Position = u_proj * u_view * vec4(in_position, 1.0);
}
"""

LINE_FRAGMENT = """
#version 330 core
in vec4 v_color;
out vec4 f_color;
void main() {
    f_color = v_color;
}
"""

GRID_VERTEX = """
#version 330 core
uniform mat4 u_view;
uniform mat4 u_proj;
uniform vec2 u_center;          // world xz of the grid centre, m
uniform float u_extent;         // half size of the grid quad, m
in vec2 in_corner;              // unit square corner in [-1, 1]^2
out vec2 v_xz;
void main() {
    v_xz = u_center + u_extent * in_corner;
    gl_Position = u_proj * u_view * vec4(v_xz.x, 0.0, v_xz.y, 1.0);
}
"""

GRID_FRAGMENT = """
#version 330 core
uniform vec2 u_center;
uniform float u_spacing;        // minor line spacing, m
uniform float u_major_every;
uniform float u_fade_distance;  // m
uniform vec4 u_minor_color;
uniform vec4 u_major_color;
in vec2 v_xz;
out vec4 f_color;

// Coverage (0..1) of grid lines about one pixel wide, for a coordinate in cell units whose
// screen-space derivative width is ``width`` (cells per pixel).
float lines(vec2 cells, vec2 width) {
    vec2 d = abs(fract(cells - 0.5) - 0.5) / max(width, vec2(1e-6));
    // lines denser than a few pixels fade out instead of aliasing
    return (1.0 - min(min(d.x, d.y), 1.0)) * (1.0 - smoothstep(0.2, 0.5, max(width.x, width.y)));
}

void main() {
    // one derivative for everything: the cell coordinates are linear in v_xz
    vec2 w = fwidth(v_xz);
    float fade = 1.0 - smoothstep(0.35 * u_fade_distance, u_fade_distance, distance(v_xz, u_center));
    if (fade < 0.002) discard;
    float minor = lines(v_xz / u_spacing, w / u_spacing);
    float major_cell = u_spacing * u_major_every;
    float major = lines(v_xz / major_cell, w / major_cell);
    vec2 axis_d = abs(v_xz) / max(w, vec2(1e-6));
    float x_axis = 1.0 - min(axis_d.y, 1.0);   // the world x axis (z = 0)
    float z_axis = 1.0 - min(axis_d.x, 1.0);   // the world z axis (x = 0)
    vec4 c = vec4(u_minor_color.rgb, u_minor_color.a * minor);
    c = mix(c, u_major_color, major);
    c = mix(c, vec4(0.85, 0.3, 0.3, 0.9), x_axis);
    c = mix(c, vec4(0.3, 0.45, 0.9, 0.9), z_axis);
    c.a *= fade;
    if (c.a < 0.002) discard;
    f_color = c;
}
"""

PRESENT_VERTEX = """
#version 330 core
// one triangle covering the viewport, no vertex buffer: texture coordinates 0..1 on screen
out vec2 v_uv;
void main() {
    vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
    v_uv = p;
    gl_Position = vec4(2.0 * p - 1.0, 0.0, 1.0);
}
"""

PRESENT_FRAGMENT = """
#version 330 core
uniform sampler2D u_image;
in vec2 v_uv;
out vec4 f_color;
void main() {
    f_color = texture(u_image, v_uv);
}
"""
