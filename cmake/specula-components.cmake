# specula's components, one library specula::<component> each (src/CMakeLists.txt), with what each
# builds on and the packages it links. Read by cmake/install.cmake, which checks the list against
# the libraries the build makes, and installed beside speculaConfig.cmake, which finds for a
# consumer only the packages of the components it asks for (and of those they build on).
#
# specula_components: every component, each after those it builds on.
# specula_<component>_needs: the components it builds on, in that order.
# specula_<component>_packages: find_package arguments, one element per package ("pkg-config:NAME"
#   for a pkg-config module, imported as PkgConfig::<NAME in upper case with '-' as '_'>).
set(specula_components core fit cost design queries render gl report serve)

set(specula_core_needs "")
set(specula_core_packages fmt TBB hwy "tomlplusplus 3")

set(specula_fit_needs core)
set(specula_fit_packages "")

set(specula_cost_needs core)
set(specula_cost_packages "")

set(specula_design_needs core fit cost)
set(specula_design_packages "")

set(specula_queries_needs core fit)
set(specula_queries_packages "")

set(specula_render_needs core)
set(specula_render_packages PNG "OpenEXR 3" tinyobjloader Freetype)

set(specula_gl_needs core render)
set(specula_gl_packages "OpenGL COMPONENTS OpenGL EGL")

set(specula_report_needs core fit cost design queries render)
set(specula_report_packages "")

set(specula_serve_needs core fit cost design queries render)
set(specula_serve_packages pkg-config:cpp-httplib)
