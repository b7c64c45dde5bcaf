# The API reference (issue 30, item 6): doxygen (Debian's, scripts/setup.sh installs it) makes
# HTML of the public headers' comments with docs/Doxyfile.in, configured into build/docs/.
# `cmake --build build --target docs` writes build/docs/api/index.html and prints doxygen's
# warnings (build/docs/doxygen-warnings.txt); the api_docs test fails on any (an undocumented
# public symbol, a broken reference). Without doxygen there is neither, and configuring says so.
find_package(Doxygen)
if(DOXYGEN_FOUND)
  set(GEOLENS_DOXYFILE ${PROJECT_BINARY_DIR}/docs/Doxyfile)
  set(GEOLENS_DOXYGEN_LOG ${PROJECT_BINARY_DIR}/docs/doxygen-warnings.txt)
  # Also makes build/docs/, where doxygen writes its log and the pages.
  configure_file(${PROJECT_SOURCE_DIR}/docs/Doxyfile.in ${GEOLENS_DOXYFILE} @ONLY)
  # Not part of `all`: the reference is made when asked for (it takes about a second).
  add_custom_target(docs
    COMMAND Doxygen::doxygen ${GEOLENS_DOXYFILE}
    COMMAND ${CMAKE_COMMAND} -E cat ${GEOLENS_DOXYGEN_LOG}
    WORKING_DIRECTORY ${PROJECT_BINARY_DIR}/docs
    COMMENT "API reference: ${PROJECT_BINARY_DIR}/docs/api/index.html"
    VERBATIM)
  if(GEOLENS_BUILD_TESTS)
    add_test(NAME api_docs
      COMMAND bash ${PROJECT_SOURCE_DIR}/scripts/api_docs.sh ${PROJECT_BINARY_DIR})
    set_tests_properties(api_docs PROPERTIES
      ENVIRONMENT "DOXYGEN=${DOXYGEN_EXECUTABLE}")
  endif()
else()
  message(STATUS "doxygen not found: no docs target or api_docs test (scripts/setup.sh "
                 "installs it)")
endif()
