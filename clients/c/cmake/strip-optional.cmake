# Writes Sync.proto (IN) to OUT without proto3's 'optional' keyword, for protoc-c 1.4.
file(READ "${IN}" text)
string(REGEX REPLACE "([\n ])optional " "\\1" text "${text}")
file(WRITE "${OUT}" "${text}")
