# RANGEKIT_GIT_COMMIT: the commit the build is made from (`git rev-parse --short=12 HEAD`), "unknown"
# outside a git checkout. Read at configure time; CMake reconfigures when HEAD or the checked-out
# branch moves (a commit, a checkout), so `--version` never names a stale commit.
set(RANGEKIT_GIT_COMMIT "unknown")
find_package(Git QUIET)
if(GIT_FOUND)
  execute_process(COMMAND ${GIT_EXECUTABLE} rev-parse --short=12 HEAD
                  WORKING_DIRECTORY ${PROJECT_SOURCE_DIR} RESULT_VARIABLE rk_git_rc
                  OUTPUT_VARIABLE rk_git_out OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
  if(rk_git_rc EQUAL 0 AND rk_git_out)
    set(RANGEKIT_GIT_COMMIT ${rk_git_out})
    # The files that change when HEAD moves: HEAD itself, the branch's ref (loose or packed).
    foreach(ref HEAD refs/heads packed-refs)
      execute_process(COMMAND ${GIT_EXECUTABLE} rev-parse --path-format=absolute --git-path ${ref}
                      WORKING_DIRECTORY ${PROJECT_SOURCE_DIR} OUTPUT_VARIABLE p
                      OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
      if(p AND EXISTS ${p} AND NOT IS_DIRECTORY ${p})
        set_property(DIRECTORY ${PROJECT_SOURCE_DIR} APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${p})
      endif()
    endforeach()
    execute_process(COMMAND ${GIT_EXECUTABLE} symbolic-ref -q HEAD WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}
                    OUTPUT_VARIABLE rk_git_branch OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
    if(rk_git_branch)
      execute_process(COMMAND ${GIT_EXECUTABLE} rev-parse --path-format=absolute --git-path ${rk_git_branch}
                      WORKING_DIRECTORY ${PROJECT_SOURCE_DIR} OUTPUT_VARIABLE p
                      OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
      if(p AND EXISTS ${p})
        set_property(DIRECTORY ${PROJECT_SOURCE_DIR} APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${p})
      endif()
    endif()
  endif()
endif()
