# The RGB-to-spectrum coefficient tables of ps_spectral, made at build time by
# rgb2spec_gen (about 10 s on 2 cores) and embedded by rgb_tables_embed.cpp. Nothing
# generated is committed.
set(PATHSPACE_RGB2SPEC_DIR "" CACHE PATH
    "Directory holding tables made by another build (e.g. build/generated/rgb2spec); empty: generate them")
set(rgb2spec_out ${CMAKE_BINARY_DIR}/generated/rgb2spec)
set(rgb2spec_files)
foreach(space srgb rec2020 dci-p3 aces2065-1)
  list(APPEND rgb2spec_files ${rgb2spec_out}/rgb2spec_${space}.bin)
endforeach()
set(rgb2spec_header ${rgb2spec_out}/rgb2spec_tables.h)

if(PATHSPACE_RGB2SPEC_DIR)
  set(rgb2spec_sources)
  foreach(f ${rgb2spec_files} ${rgb2spec_header})
    get_filename_component(n ${f} NAME)
    list(APPEND rgb2spec_sources ${PATHSPACE_RGB2SPEC_DIR}/${n})
  endforeach()
  add_custom_command(OUTPUT ${rgb2spec_files} ${rgb2spec_header}
    COMMAND ${CMAKE_COMMAND} -E make_directory ${rgb2spec_out}
    COMMAND ${CMAKE_COMMAND} -E copy ${rgb2spec_sources} ${rgb2spec_out}
    DEPENDS ${rgb2spec_sources}
    COMMENT "Copying RGB-to-spectrum tables from ${PATHSPACE_RGB2SPEC_DIR}")
else()
  add_subdirectory(${CMAKE_SOURCE_DIR}/src/spectral/gen ${CMAKE_BINARY_DIR}/rgb2spec_gen)
  add_custom_command(OUTPUT ${rgb2spec_files} ${rgb2spec_header}
    COMMAND ${CMAKE_COMMAND} -E make_directory ${rgb2spec_out}
    COMMAND rgb2spec_gen ${rgb2spec_out}
    DEPENDS rgb2spec_gen
    COMMENT "Generating RGB-to-spectrum tables (Jakob & Hanika 2019)")
endif()

target_sources(ps_spectral PRIVATE ${rgb2spec_header})
target_include_directories(ps_spectral PRIVATE ${rgb2spec_out})
set_source_files_properties(${CMAKE_SOURCE_DIR}/src/spectral/rgb_tables_embed.cpp PROPERTIES
  COMPILE_DEFINITIONS PS_RGB2SPEC_DIR="${rgb2spec_out}"
  OBJECT_DEPENDS "${rgb2spec_files};${rgb2spec_header}")
