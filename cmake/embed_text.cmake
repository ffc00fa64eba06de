# cmake -DIN=<text file> -DOUT=<.cpp> -DSYMBOL=<name> -P embed_text.cmake
# Writes OUT defining `std::string_view vilslam::embedded::SYMBOL()` that returns IN's bytes (a raw string
# literal: IN must be text without NUL bytes or the literal's closing delimiter). The texts go inline into a
# report page's <script> and <style> elements, which "</script" would end early: such a file is refused.
file(READ "${IN}" content)
set(delimiter "vilslam_embed")
string(FIND "${content}" ")${delimiter}\"" clash)
if(NOT clash EQUAL -1)
  message(FATAL_ERROR "${IN} contains the raw string delimiter )${delimiter}\"")
endif()
string(TOLOWER "${content}" lowercase)
string(FIND "${lowercase}" "</script" script_end)
if(NOT script_end EQUAL -1)
  message(FATAL_ERROR "${IN} contains \"</script\", which would end its inline <script> element")
endif()
file(WRITE "${OUT}.tmp" "// Generated from ${IN} by cmake/embed_text.cmake; do not edit.\n"
  "#include <string_view>\n"
  "namespace vilslam::embedded {\n"
  "std::string_view ${SYMBOL}() {\n"
  "  static constexpr char kText[] = R\"${delimiter}(${content})${delimiter}\";\n"
  "  return {kText, sizeof kText - 1};\n"
  "}\n"
  "}  // namespace vilslam::embedded\n")
file(RENAME "${OUT}.tmp" "${OUT}")
