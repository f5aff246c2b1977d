#pragma once

// The Kobuki base's serial protocol (Yujin Robot's published specification): a packet is
// 0xAA 0x55, a length byte N, N bytes of payload, and a checksum byte - the XOR of the length
// and payload bytes. The payload is a run of sub-payloads: an identifier byte, a length byte and
// that many data bytes, little-endian. The base streams a packet every 20 ms.

#include <cstdint>
#include <optional>
#include <vector>

namespace lodestone::drivers::kobuki {

/** Sub-payload 0x01, "basic sensor data" (15 bytes). */
struct BasicSensorData {
    std::uint16_t timestampMs{0};  ///< the base's clock, wraps at 65 536 ms
    std::uint8_t bumper{0};        ///< bits: 1 right, 2 centre, 4 left
    std::uint8_t wheelDrop{0};     ///< bits: 1 right, 2 left
    std::uint8_t cliff{0};         ///< bits: 1 right, 2 centre, 4 left
    std::uint16_t leftEncoder{0}, rightEncoder{0};  ///< ticks, wrap at 65 536
    std::int8_t leftPwm{0}, rightPwm{0};
    std::uint8_t buttons{0}, charger{0};
    std::uint8_t battery{0};  ///< [0.1 V]
    std::uint8_t overCurrent{0};
};

constexpr std::uint8_t kBasicSensorDataId = 0x01;
constexpr std::uint8_t kBasicSensorDataLength = 15;

/** Finds packets in a byte stream fed in pieces of any size: a packet split across reads is
 * joined, one with a wrong checksum or a broken sub-payload is skipped and counted, and the
 * search resumes one byte after the header it rejected (so no valid packet is missed). */
class PacketFinder {
  public:
    /** Appends bytes; returns the payloads of the packets completed by them. */
    std::vector<std::vector<std::uint8_t>> feed(const std::uint8_t* data, std::size_t size);

    std::size_t packets() const { return packets_; }
    std::size_t corrupt() const { return corrupt_; }      ///< checksum wrong
    std::size_t skippedBytes() const { return skipped_; }  ///< not part of any packet

  private:
    std::vector<std::uint8_t> buffer_;
    std::size_t packets_{0}, corrupt_{0}, skipped_{0};
};

/** The basic sensor data in a payload, if it holds one. Nullopt (and `malformed` set) when its
 * sub-payloads do not tile the payload exactly. */
std::optional<BasicSensorData> findBasicSensorData(const std::vector<std::uint8_t>& payload,
                                                   bool* malformed = nullptr);

/** A whole packet with one basic-sensor-data sub-payload, as the base sends it (for tests and
 * simulated bases). */
std::vector<std::uint8_t> encodePacket(const BasicSensorData& data);

/** Ticks travelled from `previous` to `current` on a 16-bit counter that wraps (|step| < 32 768). */
std::int32_t tickStep(std::uint16_t previous, std::uint16_t current);

}  // namespace lodestone::drivers::kobuki
