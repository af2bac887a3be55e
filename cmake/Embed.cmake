# Turns the file IN into a C++ source OUT defining
#   extern const char softsub_default_scene[];  (the file's text, NUL-terminated)
file(READ ${IN} text HEX)
string(REGEX REPLACE "([0-9a-f][0-9a-f])" "0x\\1," bytes "${text}")
file(WRITE ${OUT} "// Generated from ${IN}; do not edit.\n"
  "extern const char softsub_default_scene[];\n"
  "const char softsub_default_scene[] = {${bytes} 0x00};\n")
