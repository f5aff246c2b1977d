#include <lodestone/maps/MapNode.h>
#include <lodestone/obs/SerializedBool.h>
#include <mrpt/serialization/CArchive.h>

#include <cctype>
#include <opencv2/core.hpp>
#include <stdexcept>
#include <string_view>

namespace lodestone::maps {

IMPLEMENTS_SERIALIZABLE(CMapNode, mrpt::serialization::CSerializable, lodestone::maps)

// Version history:
//   0: id, session, timestamp, segment, lift and put-down times, keyframe flag, the camera's
//      pose on the robot; keyframe features (count, keypoints detected, per keypoint x, y,
//      size, angle, response, octave, its 32-byte descriptor and 3D point); the magnetometer
//      readings (count; timestamp, label, field x y z, the sensor's pose).
uint8_t CMapNode::serializeGetVersion() const { return 0; }

bool isMapLabel(const std::string& label) {
    if (label.empty() || label.size() > 256) return false;
    // Letters, digits and a few marks only: the manifest lists the labels in an INI value, where
    // a backslash continues the line, ';' and '#' start comments and '$' substitutes.
    for (const unsigned char c : label)
        if (!std::isalnum(c) &&
            std::string_view("_-.:/+").find(static_cast<char>(c)) == std::string_view::npos)
            return false;
    return true;
}

// More segments than any map holds (a kidnap each): a damaged field.
constexpr std::int32_t kMostSegments = 1 << 24;

namespace {

void writePose(mrpt::serialization::CArchive& out, const Eigen::Isometry3d& T) {
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c) out << T.matrix()(r, c);
}

Eigen::Isometry3d readPose(mrpt::serialization::CArchive& in) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c) in >> T.matrix()(r, c);
    return T;
}

}  // namespace

void CMapNode::serializeTo(mrpt::serialization::CArchive& out) const {
    const auto& r = record;
    out << id << session << r.timestamp << static_cast<std::int32_t>(r.segment) << r.liftTime
        << r.putDownTime << r.keyframe;
    writePose(out, r.T_robot_camera);
    const bool hasFeatures = r.features != nullptr;
    out << hasFeatures;
    if (hasFeatures) {
        const auto& f = *r.features;
        out << static_cast<std::uint32_t>(f.size()) << static_cast<std::uint64_t>(f.detected);
        for (std::size_t i = 0; i < f.size(); ++i) {
            const auto& k = f.keypoints[i];
            out << k.pt.x << k.pt.y << k.size << k.angle << k.response
                << static_cast<std::int32_t>(k.octave);
            out.WriteBuffer(f.descriptors.ptr(static_cast<int>(i)), 32);
            const auto p = f.points.col(static_cast<Eigen::Index>(i));
            out << p.x() << p.y() << p.z();
        }
    }
    out << static_cast<std::uint32_t>(r.magnetic.size());
    for (const auto& m : r.magnetic)
        out << m.timestamp << m.sensorLabel << m.field.x << m.field.y << m.field.z << m.sensorPose;
}

void CMapNode::serializeFrom(mrpt::serialization::CArchive& in, uint8_t version) {
    switch (version) {
        case 0: {
            graphslam::NodeRecord r;
            std::int32_t segment = 0;
            in >> id >> session >> r.timestamp >> segment >> r.liftTime >> r.putDownTime;
            r.keyframe = obs::readBool(in, "CMapNode", "keyframe");
            if (segment < 0 || segment > kMostSegments)
                throw std::runtime_error("segment " + std::to_string(segment) + " out of range");
            r.segment = segment;
            r.T_robot_camera = readPose(in);
            if (obs::readBool(in, "CMapNode", "has_features")) {
                auto f = std::make_shared<vision::FrameFeatures>();
                std::uint32_t n = 0;
                std::uint64_t detected = 0;
                in >> n >> detected;
                f->detected = detected;
                // (a damaged count fails on the data, not on a huge allocation up front:
                // the keypoints are read one by one)
                std::vector<std::uint8_t> descriptors;
                std::vector<float> points;
                for (std::uint32_t i = 0; i < n; ++i) {
                    cv::KeyPoint k;
                    std::int32_t octave = 0;
                    in >> k.pt.x >> k.pt.y >> k.size >> k.angle >> k.response >> octave;
                    k.octave = octave;
                    f->keypoints.push_back(k);
                    std::uint8_t d[32];
                    if (in.ReadBuffer(d, 32) != 32)
                        throw std::runtime_error("a keyframe descriptor is cut short");
                    descriptors.insert(descriptors.end(), d, d + 32);
                    float x = 0, y = 0, z = 0;
                    in >> x >> y >> z;
                    points.insert(points.end(), {x, y, z});
                }
                f->descriptors = cv::Mat(static_cast<int>(n), 32, CV_8UC1);
                if (n) std::copy(descriptors.begin(), descriptors.end(), f->descriptors.data);
                f->points = Eigen::Map<const Eigen::Matrix3Xf>(points.data(), 3, n);
                r.features = std::move(f);
            }
            std::uint32_t readings = 0;
            in >> readings;
            for (std::uint32_t i = 0; i < readings; ++i) {
                graphslam::MagneticSample m;
                in >> m.timestamp >> m.sensorLabel >> m.field.x >> m.field.y >> m.field.z >>
                    m.sensorPose;
                if (!isMapLabel(m.sensorLabel))
                    throw std::runtime_error("a magnetometer label that is not printable text");
                r.magnetic.push_back(std::move(m));
            }
            record = std::move(r);
            break;
        }
        default:
            MRPT_THROW_UNKNOWN_SERIALIZATION_VERSION(version);
    }
}

}  // namespace lodestone::maps
