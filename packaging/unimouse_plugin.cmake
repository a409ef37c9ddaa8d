# SPDX-License-Identifier: GPL-3.0-or-later
# Included by the build and by the installed package config (find_package(unimouse)), so a plugin
# built in this tree and one built outside it come out alike.

# Adds target unimouse_NAME: a component plugin, the loadable module libunimouse_NAME.so (the
# file name unimouse looks for in its plugin directories) that exports unimouse_plugin_v1 and
# nothing else.
function(unimouse_add_component_plugin name)
  add_library(unimouse_${name} MODULE ${ARGN})
  target_link_libraries(unimouse_${name} PRIVATE unimouse::plugin_api)
  target_compile_features(unimouse_${name} PRIVATE cxx_std_20)
  set_target_properties(unimouse_${name} PROPERTIES PREFIX "lib" OUTPUT_NAME unimouse_${name}
    CXX_VISIBILITY_PRESET hidden VISIBILITY_INLINES_HIDDEN ON)
endfunction()
