// The small helpers of the .map data: idDict-like key lookup and entity search.

#include "af/text/map_file.h"
#include "af/text/strings.h"

#include <utility>

namespace af {

const MapKeyValue* MapKeyValues::find(std::string_view key) const {
    for (const MapKeyValue& kv : items_)
        if (equalsIgnoreCase(kv.key, key)) return &kv;
    return nullptr;
}

std::string_view MapKeyValues::value(std::string_view key, std::string_view fallback) const {
    const MapKeyValue* kv = find(key);
    return kv ? std::string_view(kv->value) : fallback;
}

void MapKeyValues::set(std::string_view key, std::string_view value, SourceLocation where) {
    for (MapKeyValue& kv : items_) {
        if (!equalsIgnoreCase(kv.key, key)) continue;
        kv.value = value;
        kv.where = where;
        return;
    }
    items_.push_back({std::string(key), std::string(value), where});
}

const MapEntity* MapFile::findEntity(std::string_view name) const {
    for (const MapEntity& e : entities)
        if (const MapKeyValue* kv = e.keys.find("name"); kv && equalsIgnoreCase(kv->value, name)) return &e;
    return nullptr;
}

MapEntity* MapFile::findEntity(std::string_view name) {
    return const_cast<MapEntity*>(std::as_const(*this).findEntity(name));
}

std::string materialPath(const MapFile& map, std::string_view material) {
    if (map.version < 2) return "textures/" + std::string(material);
    return std::string(material);
}

}  // namespace af
