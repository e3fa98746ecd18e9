# gl_tests: tests/gl/*_test.cpp, with the viewer's library for viewer_test.cpp and the
# shader unit tests' harness (src/pbrkit/gl/testing).
pbrkit_add_tests(gl pbrkit_viewer pbrkit_gl_testing)
