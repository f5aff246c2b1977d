#pragma once

#include <memory>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

namespace lodestone::graphslam {

/** A JSON object built in insertion order, for report.json: numbers, strings, booleans, number
 * lists and nested objects are all it needs. Non-finite numbers are written as null. */
class JsonObject {
  public:
    JsonObject& set(const std::string& key, double value);
    JsonObject& set(const std::string& key, long long value);
    JsonObject& set(const std::string& key, int value) { return set(key, static_cast<long long>(value)); }
    JsonObject& set(const std::string& key, std::size_t value) { return set(key, static_cast<long long>(value)); }
    JsonObject& set(const std::string& key, bool value);
    JsonObject& set(const std::string& key, const std::string& value);
    JsonObject& set(const std::string& key, const char* value) { return set(key, std::string(value)); }
    JsonObject& set(const std::string& key, const std::vector<double>& values);
    JsonObject& set(const std::string& key, const JsonObject& object);
    /** Objects in a list (e.g. one per rejected loop closure). */
    JsonObject& set(const std::string& key, const std::vector<JsonObject>& objects);

    void write(std::ostream& out, int indent = 0) const;
    std::string str() const;
    bool empty() const { return members_.empty(); }

  private:
    struct Member {
        std::string key;
        std::string raw;                                 // a serialized scalar or number list
        std::shared_ptr<const JsonObject> object;        // or a nested object
        std::shared_ptr<const std::vector<JsonObject>> list;  // or a list of objects
    };
    JsonObject& put(Member m);
    std::vector<Member> members_;
};

/** `text` as a JSON string literal, quotes included. */
std::string jsonString(const std::string& text);

}  // namespace lodestone::graphslam
