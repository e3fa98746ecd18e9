# gl_tests: tests/gl/*_test.cpp, with the shader unit tests' harness
# (src/pbrkit/gl/testing).
pbrkit_add_tests(gl pbrkit_gl_testing)
