# `morphex serve` (issue 46): over HTTP on 127.0.0.1 (listing, queries, an upload, glb and
# thumbnails, bad requests), and its page in headless Chromium (skipped only without chromium,
# which scripts/setup installs). Label: serve; the browser test also: browser.
find_package(Python3 COMPONENTS Interpreter QUIET)
if(Python3_Interpreter_FOUND)
  add_test(NAME serve.http COMMAND ${Python3_EXECUTABLE}
    ${CMAKE_CURRENT_SOURCE_DIR}/serve/serve_http.py $<TARGET_FILE:morphex>
    ${CMAKE_CURRENT_SOURCE_DIR}/data ${PROJECT_BINARY_DIR}/serve-http)
  set_tests_properties(serve.http PROPERTIES LABELS serve TIMEOUT 300)
  add_test(NAME serve.browser COMMAND ${Python3_EXECUTABLE}
    ${CMAKE_CURRENT_SOURCE_DIR}/serve/serve_browser.py $<TARGET_FILE:morphex>
    ${CMAKE_CURRENT_SOURCE_DIR}/data ${PROJECT_BINARY_DIR}/serve-browser)
  set_tests_properties(serve.browser PROPERTIES LABELS "serve;browser" TIMEOUT 900
                       SKIP_RETURN_CODE 77)
endif()
