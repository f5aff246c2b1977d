// The Kobuki protocol and CKobukiBase against a pseudo-terminal that speaks it.
#include <gtest/gtest.h>
#include <lodestone/drivers/kobuki/CKobukiBase.h>
#include <lodestone/drivers/kobuki/KobukiProtocol.h>
#include <lodestone/drivers/registerDrivers.h>
#include <lodestone/obs/CObservationWheelDrop.h>
#include <lodestone/obs/registerAllClasses.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/obs/CObservationComment.h>
#include <mrpt/obs/CObservationOdometry.h>

#include <chrono>
#include <cmath>
#include <thread>

#include <pty.h>
#include <unistd.h>

using namespace lodestone::drivers;
using kobuki::BasicSensorData;

TEST(KobukiProtocol, PacketsRoundTripWhateverTheReadSizes) {
    BasicSensorData a;
    a.timestampMs = 1234;
    a.wheelDrop = 2;
    a.leftEncoder = 65530;
    a.rightEncoder = 7;
    a.leftPwm = -3;
    a.battery = 162;
    const auto bytes = kobuki::encodePacket(a);
    ASSERT_EQ(bytes.size(), 3u + 17u + 1u);
    kobuki::PacketFinder finder;
    std::vector<std::vector<std::uint8_t>> got;
    for (const auto b : bytes) {  // a byte at a time: the packet is joined
        for (auto& p : finder.feed(&b, 1)) got.push_back(p);
    }
    ASSERT_EQ(got.size(), 1u);
    const auto back = kobuki::findBasicSensorData(got[0]);
    ASSERT_TRUE(back);
    EXPECT_EQ(back->timestampMs, 1234);
    EXPECT_EQ(back->wheelDrop, 2);
    EXPECT_EQ(back->leftEncoder, 65530);
    EXPECT_EQ(back->rightEncoder, 7);
    EXPECT_EQ(back->leftPwm, -3);
    EXPECT_EQ(back->battery, 162);
}

TEST(KobukiProtocol, ACorruptPacketIsSkippedAndCountedAndTheNextOneFound) {
    BasicSensorData d;
    auto good1 = kobuki::encodePacket(d);
    d.leftEncoder = 100;
    auto bad = kobuki::encodePacket(d);
    bad[8] ^= 0x40;  // a flipped bit: the checksum no longer holds
    d.leftEncoder = 200;
    auto good2 = kobuki::encodePacket(d);
    std::vector<std::uint8_t> stream = {0x01, 0xAA, 0x13, 0x55};  // noise, a lone header byte
    for (const auto* p : {&good1, &bad, &good2}) stream.insert(stream.end(), p->begin(), p->end());
    stream.insert(stream.end(), good1.begin(), good1.begin() + 9);  // a partial packet: kept
    kobuki::PacketFinder finder;
    const auto packets = finder.feed(stream.data(), stream.size());
    ASSERT_EQ(packets.size(), 2u);
    EXPECT_EQ(kobuki::findBasicSensorData(packets[1])->leftEncoder, 200);
    EXPECT_EQ(finder.corrupt(), 1u);
    const auto rest = finder.feed(good1.data() + 9, good1.size() - 9);
    EXPECT_EQ(rest.size(), 1u);  // the partial one completed
    // A payload whose sub-payload claims more bytes than there are.
    bool malformed = false;
    EXPECT_FALSE(kobuki::findBasicSensorData({0x01, 0x0F, 1, 2}, &malformed));
    EXPECT_TRUE(malformed);
}

TEST(KobukiProtocol, TickStepsAcrossTheWrap) {
    EXPECT_EQ(kobuki::tickStep(65530, 4), 10);
    EXPECT_EQ(kobuki::tickStep(4, 65530), -10);
    EXPECT_EQ(kobuki::tickStep(100, 100), 0);
}

namespace {
// A pseudo-terminal: the test writes the base's bytes on the master, the driver reads the
// slave as its serial port.
struct Pty {
    int master{-1}, slave{-1};
    std::string name;
    Pty() {
        char buf[128];
        if (openpty(&master, &slave, buf, nullptr, nullptr) != 0) throw std::runtime_error("openpty failed");
        name = buf;
    }
    ~Pty() {
        if (master >= 0) ::close(master);
        if (slave >= 0) ::close(slave);
    }
    void send(const std::vector<std::uint8_t>& bytes) const {
        ASSERT_EQ(::write(master, bytes.data(), bytes.size()), static_cast<ssize_t>(bytes.size()));
    }
};
}  // namespace

TEST(CKobukiBase, TicksWheelDropAndACorruptPacketOverAPseudoTerminal) {
    lodestone::registerAllClasses();
    registerDrivers();
    Pty pty;
    auto sensor = mrpt::hwdrivers::CGenericSensor::createSensorPtr("CKobukiBase");
    ASSERT_TRUE(sensor);
    mrpt::config::CConfigFileMemory ini("[BASE]\nsensorLabel = BASE\nserial_port = " + pty.name +
                                        "\nread_timeout_ms = 20\n");
    sensor->loadConfig(ini, "BASE");
    sensor->initialize();
    auto& base = dynamic_cast<CKobukiBase&>(*sensor);

    // 40 packets 20 ms apart (base clock), both wheels forward 50 ticks a packet, starting
    // near the 16-bit wrap; the left wheel drops at packet 30; packet 20 arrives damaged.
    BasicSensorData d;
    const int kPackets = 40, kStep = 50;
    for (int i = 0; i < kPackets; ++i) {
        d.timestampMs = static_cast<std::uint16_t>(65000 + 20 * i);
        d.leftEncoder = static_cast<std::uint16_t>(64000 + kStep * i);
        d.rightEncoder = static_cast<std::uint16_t>(64000 + kStep * i);
        d.wheelDrop = i >= 30 ? 0x02 : 0;
        auto bytes = kobuki::encodePacket(d);
        if (i == 20) bytes[10] ^= 0xFF;
        pty.send(bytes);
    }
    std::vector<mrpt::obs::CObservation::Ptr> got;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
    while (base.packets() + base.corruptPackets() < kPackets && std::chrono::steady_clock::now() < deadline) {
        base.doProcess();
        for (auto& [t, o] : base.getObservations()) got.push_back(std::dynamic_pointer_cast<mrpt::obs::CObservation>(o));
    }
    EXPECT_EQ(base.packets(), static_cast<std::size_t>(kPackets - 1));
    EXPECT_EQ(base.corruptPackets(), 1u);
    std::vector<mrpt::obs::CObservationOdometry::Ptr> odo;
    std::vector<lodestone::obs::CObservationWheelDrop::Ptr> drops;
    std::size_t comments = 0;
    for (const auto& o : got) {
        if (auto p = std::dynamic_pointer_cast<mrpt::obs::CObservationOdometry>(o)) odo.push_back(p);
        if (auto p = std::dynamic_pointer_cast<lodestone::obs::CObservationWheelDrop>(o)) drops.push_back(p);
        comments += IS_CLASS(*o, mrpt::obs::CObservationComment);
    }
    ASSERT_EQ(odo.size(), static_cast<std::size_t>(kPackets - 1));
    // Ticks unwrapped across 65535 -> 0: absolute counts grow by 50 a packet (two across the
    // damaged one).
    EXPECT_EQ(odo.back()->encoderLeftTicks - odo.front()->encoderLeftTicks, kStep * (kPackets - 1));
    EXPECT_TRUE(odo.back()->hasEncodersInfo);
    // Straight ahead: 1950 ticks of a 0.035 m wheel at 2578.33 ticks a turn.
    const double metres = kStep * (kPackets - 1) / 2578.33 * 2 * M_PI * 0.035;
    EXPECT_NEAR(odo.back()->odometry.x(), metres, 1e-6);
    EXPECT_NEAR(odo.back()->odometry.y(), 0.0, 1e-9);
    ASSERT_TRUE(odo.back()->hasVelocities);
    EXPECT_NEAR(odo.back()->velocityLocal.vx, kStep / 2578.33 * 2 * M_PI * 0.035 / 0.020, 1e-6);
    // The first state and the drop.
    ASSERT_EQ(drops.size(), 2u);
    EXPECT_FALSE(drops[0]->lifted());
    EXPECT_TRUE(drops[1]->leftDropped);
    EXPECT_FALSE(drops[1]->rightDropped);
    EXPECT_EQ(comments, 1u);  // bumper and cliff never changed: the first state only
}

TEST(CKobukiBase, AMissingPortIsAnErrorNamingSectionAndPort) {
    registerDrivers();
    auto sensor = mrpt::hwdrivers::CGenericSensor::createSensorPtr("CKobukiBase");
    mrpt::config::CConfigFileMemory ini("[BASE]\nserial_port = /dev/no-such-kobuki\n");
    sensor->loadConfig(ini, "BASE");
    try {
        sensor->initialize();
        FAIL() << "opened a port that does not exist";
    } catch (const std::exception& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("sensor section 'BASE'"), std::string::npos) << what;
        EXPECT_NE(what.find("/dev/no-such-kobuki"), std::string::npos) << what;
    }
}
