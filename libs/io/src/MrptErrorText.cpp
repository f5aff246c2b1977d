#include <lodestone/io/MrptErrorText.h>

namespace lodestone::io {

// MRPT exception texts nest one block per object being read ("Exception while parsing typed
// object 'X' from FILE", then the inner one's), each with a call trace. A user needs the chain
// of classes and the innermost message: "CActionCollection > CPosePDFGaussian: <message>".
std::string condensedMrptError(const std::string& text) {
    const std::string kMessage = "Message:";
    const std::string kParsing = "Exception while parsing typed object '";
    std::string chain, innermost;
    bool afterOriginal = false;
    std::size_t start = 0;
    while (start < text.size()) {
        std::size_t end = text.find('\n', start);
        if (end == std::string::npos) end = text.size();
        const std::string line = text.substr(start, end - start);
        start = end + 1;
        const auto at = line.find(kMessage);
        if (at == std::string::npos) {
            // A std::exception thrown inside a deserializer: its text follows "Original
            // exception:" (and a "==== MRPT exception ====" banner) on a line of its own.
            if (line.rfind("Original exception:", 0) == 0) {
                afterOriginal = true;
            } else if (line.find("MRPT exception") == std::string::npos && !line.empty()) {
                if (afterOriginal && innermost.empty()) innermost = line;
                afterOriginal = false;
            }
            continue;
        }
        afterOriginal = false;
        std::string message = line.substr(at + kMessage.size());
        message.erase(0, message.find_first_not_of(' '));
        if (message.rfind(kParsing, 0) == 0) {
            const auto close = message.find('\'', kParsing.size());
            const std::string name = message.substr(kParsing.size(), close - kParsing.size());
            const bool isClassName = !name.empty() && name.find_first_not_of(
                "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_:") == std::string::npos;
            if (isClassName) chain += (chain.empty() ? "" : " > ") + name;
        } else if (innermost.empty()) {
            innermost = message;
        }
    }
    if (innermost.empty() && chain.empty()) {  // not MRPT's format: its first line
        const auto first = text.find_first_not_of(" \t=\n");
        return first == std::string::npos ? text : text.substr(first, text.find('\n', first) - first);
    }
    if (innermost.empty()) innermost = "unreadable object";
    if (innermost.find("(EOF?)") != std::string::npos) innermost = "the file ends inside this entry";
    return chain.empty() ? innermost : chain + ": " + innermost;
}

}  // namespace lodestone::io
