# gl_tests: tests/gl/*_test.cpp, with the viewer's library for viewer_test.cpp.
pbrkit_add_tests(gl pbrkit_viewer)
