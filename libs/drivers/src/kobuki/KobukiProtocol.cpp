#include <lodestone/drivers/kobuki/KobukiProtocol.h>

namespace lodestone::drivers::kobuki {

namespace {
constexpr std::uint8_t kHeader0 = 0xAA, kHeader1 = 0x55;
}  // namespace

std::vector<std::vector<std::uint8_t>> PacketFinder::feed(const std::uint8_t* data, std::size_t size) {
    buffer_.insert(buffer_.end(), data, data + size);
    std::vector<std::vector<std::uint8_t>> out;
    std::size_t at = 0;
    while (true) {
        // The next header.
        std::size_t h = at;
        while (h + 1 < buffer_.size() && !(buffer_[h] == kHeader0 && buffer_[h + 1] == kHeader1)) ++h;
        if (h + 1 >= buffer_.size()) {  // none: keep a last 0xAA, it may start one
            const std::size_t keep = !buffer_.empty() && buffer_.back() == kHeader0 ? 1 : 0;
            skipped_ += buffer_.size() - keep - at;
            at = buffer_.size() - keep;
            break;
        }
        skipped_ += h - at;
        at = h;
        if (at + 3 > buffer_.size()) break;  // the length has not arrived
        const std::size_t length = buffer_[at + 2];
        const std::size_t total = 3 + length + 1;
        if (at + total > buffer_.size()) break;  // the rest has not arrived
        std::uint8_t x = 0;
        for (std::size_t i = at + 2; i < at + total; ++i) x ^= buffer_[i];
        if (x != 0 || length < 2) {
            ++corrupt_;
            ++skipped_;
            ++at;  // a false header, or a damaged packet: look again from the next byte
            continue;
        }
        out.emplace_back(buffer_.begin() + static_cast<std::ptrdiff_t>(at + 3),
                         buffer_.begin() + static_cast<std::ptrdiff_t>(at + 3 + length));
        ++packets_;
        at += total;
    }
    buffer_.erase(buffer_.begin(), buffer_.begin() + static_cast<std::ptrdiff_t>(at));
    return out;
}

std::optional<BasicSensorData> findBasicSensorData(const std::vector<std::uint8_t>& p,
                                                   bool* malformed) {
    if (malformed) *malformed = false;
    std::optional<BasicSensorData> found;
    std::size_t i = 0;
    while (i < p.size()) {
        if (i + 2 > p.size() || i + 2 + p[i + 1] > p.size()) {
            if (malformed) *malformed = true;
            return std::nullopt;
        }
        const std::uint8_t id = p[i], len = p[i + 1];
        const std::uint8_t* d = p.data() + i + 2;
        if (id == kBasicSensorDataId && len == kBasicSensorDataLength) {
            BasicSensorData b;
            const auto u16 = [&](int k) {
                return static_cast<std::uint16_t>(d[k] | (static_cast<std::uint16_t>(d[k + 1]) << 8));
            };
            b.timestampMs = u16(0);
            b.bumper = d[2];
            b.wheelDrop = d[3];
            b.cliff = d[4];
            b.leftEncoder = u16(5);
            b.rightEncoder = u16(7);
            b.leftPwm = static_cast<std::int8_t>(d[9]);
            b.rightPwm = static_cast<std::int8_t>(d[10]);
            b.buttons = d[11];
            b.charger = d[12];
            b.battery = d[13];
            b.overCurrent = d[14];
            found = b;
        }
        i += 2 + len;
    }
    return found;
}

std::vector<std::uint8_t> encodePacket(const BasicSensorData& b) {
    std::vector<std::uint8_t> packet;
    packet.reserve(3 + 2 + kBasicSensorDataLength + 1);
    const auto byte = [&](std::uint8_t v) { packet.push_back(v); };
    const auto u16 = [&](std::uint16_t v) {
        byte(static_cast<std::uint8_t>(v & 0xFF));
        byte(static_cast<std::uint8_t>(v >> 8));
    };
    byte(kHeader0);
    byte(kHeader1);
    byte(2 + kBasicSensorDataLength);  // one sub-payload: identifier, length, data
    byte(kBasicSensorDataId);
    byte(kBasicSensorDataLength);
    u16(b.timestampMs);
    byte(b.bumper);
    byte(b.wheelDrop);
    byte(b.cliff);
    u16(b.leftEncoder);
    u16(b.rightEncoder);
    byte(static_cast<std::uint8_t>(b.leftPwm));
    byte(static_cast<std::uint8_t>(b.rightPwm));
    byte(b.buttons);
    byte(b.charger);
    byte(b.battery);
    byte(b.overCurrent);
    std::uint8_t x = 0;
    for (std::size_t i = 2; i < packet.size(); ++i) x ^= packet[i];
    byte(x);
    return packet;
}

std::int32_t tickStep(std::uint16_t previous, std::uint16_t current) {
    return static_cast<std::int16_t>(static_cast<std::uint16_t>(current - previous));
}

}  // namespace lodestone::drivers::kobuki
