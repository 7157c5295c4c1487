//@ The shader_test's vertex shader (export/shader_test.cpp fills it; export/text_template.hpp
//@ says how): the GL harness's, clip coordinates to gl_Position untouched and every varying
//@ with its qualifier and type, plus the triangle's index as a flat int (softpipe gives no
//@ gl_PrimitiveID without a geometry shader).
//@ ATTRIBUTES: per varying k, its attribute a<k> at location k + 1 and its output v<k>; then
//@ the distances' attributes a_distances<j> (vec4s, locations left to the linker) and the
//@ redeclared gl_ClipDistance / gl_CullDistance.
//@ COPIES: per varying k, "v<k> = a<k>;", then each distance from its attribute.
//@ EXTENSIONS: GL_ARB_cull_distance's directive where the case has cull distances.
#version 330 core
@EXTENSIONS@
layout(location = 0) in vec4 a_clip;
@ATTRIBUTES@
layout(location = @TRIANGLE_LOCATION@) in int a_triangle;
flat out int v_triangle;
void main() {
  gl_Position = a_clip;
@COPIES@
  v_triangle = a_triangle;
}
