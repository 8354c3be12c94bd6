#pragma once
// Map text for tests that need a world of their own: brushDef3 brushes given by their planes
// ("a b c d" for the plane a·x + b·y + c·z + d = 0, normal pointing out), in a worldspawn.

#include <string>
#include <vector>

namespace af::test {

inline std::string brushDef3(const std::vector<std::string>& planes) {
    const std::string textureAxes = " ( ( 0.0078125 0 0 ) ( 0 0.0078125 0 ) ) \"textures/af/floor\" 0 0 0\n";
    std::string text = "{\n brushDef3\n {\n";
    for (const std::string& p : planes) text += "  ( " + p + " )" + textureAxes;
    return text + " }\n}\n";
}

inline std::string worldspawnMap(const std::vector<std::string>& brushes) {
    std::string text = "Version 2\n{\n\"classname\" \"worldspawn\"\n";
    for (const std::string& b : brushes) text += b;
    return text + "}\n";
}

// A floor 1024 units square with its top at z = 0, and a wall beside the origin: x from 2 to
// 100, y from −64 to 64, up to z = 80. A figure dropped at (0, 0) leaning forward reaches into it.
inline std::string floorBesideWallMap() {
    return worldspawnMap({brushDef3({"0 0 -1 -16", "0 0 1 0", "0 -1 0 -512", "1 0 0 -512", "0 1 0 -512", "-1 0 0 -512"}),
                          brushDef3({"0 0 -1 0", "0 0 1 -80", "0 -1 0 -64", "1 0 0 -100", "0 1 0 -64", "-1 0 0 2"})});
}

}  // namespace af::test
