# Doxygen's input filter for the public headers (Doxyfile, INPUT_FILTER): sphys documents with
# plain // comments, which Doxygen would skip, so each is read as a documentation comment.
# A comment line, /// already or //: < and > are text, not HTML tags (<disable_collisions ...>).
/^[[:space:]]*\/\/([^/]|$)/ {
  s#<#\\<#g
  s#>#\\>#g
  s#^([[:space:]]*)//[[:space:]]?#\1/// #
}
# A comment after code on its line documents that code.
s#^([^/"]*[;,{])[[:space:]]+//[[:space:]]?(.*)$#\1  ///< \2#
# Every header documented as a file, so that its macros are in the reference (and must be
# documented), on its first line so that the warnings' line numbers stay the header's.
1s#$#  /** @file */#
