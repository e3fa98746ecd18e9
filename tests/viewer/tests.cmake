# viewer_tests: tests/viewer/*_test.cpp, the viewer's (apps/viewer) and `pbrkit view`'s
# tests, with the viewer's library for those that drive it in-process.
pbrkit_add_tests(viewer pbrkit_viewer)
