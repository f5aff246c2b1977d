# Helpers that give every lodestone library and app the same shape:
#   lodestone_add_library(<lib> SOURCES ... DEPENDS ...) -> target lodestone_<lib>, alias
#   lodestone::<lib>, headers under libs/<lib>/include, exported as lodestone::<lib>.
#   lodestone_add_app(<name> SOURCES ... DEPENDS ...)    -> an installed executable, with the
#                                                           executable hooks (below).

set(LODESTONE_WARNING_FLAGS -Wall -Wextra -Wpedantic)
# What every Lodestone executable (apps, tests, fuzz targets) links in directly: the allocation
# hooks that bound a damaged rawlog entry (libs/memguard/hooks) and libjpeg's error handler
# made to throw (libs/io/hooks). Object libraries: linked directly, never transitively.
set(LODESTONE_EXECUTABLE_HOOKS lodestone_allocation_hooks lodestone_jpeg_error_hook)

function(lodestone_apply_common_flags target)
    target_compile_options(${target} PRIVATE ${LODESTONE_WARNING_FLAGS})
    if(LODESTONE_SANITIZE)
        target_compile_options(${target} PRIVATE -fsanitize=address,undefined
            -fno-sanitize-recover=undefined -fno-omit-frame-pointer)
        target_link_options(${target} PUBLIC -fsanitize=address,undefined)
    endif()
    if(LODESTONE_FUZZ)
        # Coverage feedback for libFuzzer from every Lodestone target (MRPT is not instrumented).
        target_compile_options(${target} PRIVATE -fsanitize=fuzzer-no-link)
    endif()
endfunction()

function(lodestone_add_library lib)
    cmake_parse_arguments(ARG "" "" "SOURCES;PUBLIC_DEPENDS;PRIVATE_DEPENDS" ${ARGN})
    set(target lodestone_${lib})
    add_library(${target} ${ARG_SOURCES})
    add_library(lodestone::${lib} ALIAS ${target})
    set_target_properties(${target} PROPERTIES
        EXPORT_NAME ${lib}
        OUTPUT_NAME lodestone_${lib}
        VERSION ${PROJECT_VERSION}
        SOVERSION ${PROJECT_VERSION_MAJOR})
    target_include_directories(${target} PUBLIC
        $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>
        $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
    target_link_libraries(${target} PUBLIC ${ARG_PUBLIC_DEPENDS} PRIVATE ${ARG_PRIVATE_DEPENDS})
    target_compile_features(${target} PUBLIC cxx_std_17)
    lodestone_apply_common_flags(${target})
    install(TARGETS ${target} EXPORT lodestoneTargets
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
    install(DIRECTORY include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endfunction()

function(lodestone_add_app name)
    cmake_parse_arguments(ARG "" "" "SOURCES;DEPENDS" ${ARGN})
    add_executable(${name} ${ARG_SOURCES})
    target_link_libraries(${name} PRIVATE ${ARG_DEPENDS} ${LODESTONE_EXECUTABLE_HOOKS})
    lodestone_apply_common_flags(${name})
    install(TARGETS ${name} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endfunction()
