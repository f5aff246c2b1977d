#include <lodestone/graphslam/ReportJson.h>

#include <cmath>
#include <cstdio>
#include <sstream>

namespace lodestone::graphslam {

namespace {
std::string number(double v) {
    if (!std::isfinite(v)) return "null";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.15g", v);  // 15: epoch timestamps keep their ms
    return buf;
}
}  // namespace

std::string jsonString(const std::string& text) {
    std::string out = "\"";
    for (const char ch : text) {
        const auto c = static_cast<unsigned char>(ch);
        switch (c) {
            case '"': out += "\\\""; break;
            case '\\': out += "\\\\"; break;
            case '\n': out += "\\n"; break;
            case '\t': out += "\\t"; break;
            case '\r': out += "\\r"; break;
            default:
                if (c < 0x20) {
                    char buf[8];
                    std::snprintf(buf, sizeof buf, "\\u%04x", c);
                    out += buf;
                } else {
                    out += ch;
                }
        }
    }
    return out + "\"";
}

JsonObject& JsonObject::put(Member m) {
    for (auto& existing : members_) {
        if (existing.key == m.key) {
            existing = std::move(m);
            return *this;
        }
    }
    members_.push_back(std::move(m));
    return *this;
}

JsonObject& JsonObject::set(const std::string& key, double value) { return put({key, number(value), {}, {}}); }
JsonObject& JsonObject::set(const std::string& key, long long value) {
    return put({key, std::to_string(value), {}, {}});
}
JsonObject& JsonObject::set(const std::string& key, bool value) {
    return put({key, value ? "true" : "false", {}, {}});
}
JsonObject& JsonObject::set(const std::string& key, const std::string& value) {
    return put({key, jsonString(value), {}, {}});
}
JsonObject& JsonObject::set(const std::string& key, const std::vector<double>& values) {
    std::string raw = "[";
    for (std::size_t i = 0; i < values.size(); ++i) raw += (i ? ", " : "") + number(values[i]);
    return put({key, raw + "]", {}, {}});
}
JsonObject& JsonObject::set(const std::string& key, const JsonObject& object) {
    return put({key, {}, std::make_shared<JsonObject>(object), {}});
}
JsonObject& JsonObject::set(const std::string& key, const std::vector<JsonObject>& objects) {
    return put({key, {}, {}, std::make_shared<std::vector<JsonObject>>(objects)});
}

void JsonObject::write(std::ostream& out, int indent) const {
    const std::string pad(indent + 2, ' '), end(indent, ' ');
    out << "{";
    for (std::size_t i = 0; i < members_.size(); ++i) {
        const auto& m = members_[i];
        out << (i ? "," : "") << "\n" << pad << jsonString(m.key) << ": ";
        if (m.object) {
            m.object->write(out, indent + 2);
        } else if (m.list) {
            out << "[";
            for (std::size_t k = 0; k < m.list->size(); ++k) {
                out << (k ? "," : "") << "\n" << pad << "  ";
                (*m.list)[k].write(out, indent + 4);
            }
            out << (m.list->empty() ? "]" : "\n" + pad + "]");
        } else {
            out << m.raw;
        }
    }
    out << (members_.empty() ? "}" : "\n" + end + "}");
}

std::string JsonObject::str() const {
    std::ostringstream s;
    write(s);
    return s.str();
}

}  // namespace lodestone::graphslam
