# The image tests also write files with OpenEXR and stb directly (NaN/Inf/negative samples,
# raw half counts, a JPEG), independently of the code under test.
pbrkit_add_tests(image OpenEXR::OpenEXR PkgConfig::STB)
