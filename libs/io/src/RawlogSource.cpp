#include <lodestone/io/EntryContents.h>
#include <lodestone/io/ImagesDirectory.h>
#include <lodestone/io/RawlogReadError.h>
#include <lodestone/io/RawlogSource.h>
#include <mrpt/img/CImage.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>

#include <cstring>
#include <mrpt/obs/CObservationOdometry.h>

namespace lodestone::io {

using mrpt::obs::CObservation;

RawlogSource::RawlogSource(const std::string& path) : RawlogSource(path, Options{}) {}

RawlogSource::RawlogSource(const std::string& path, Options options)
    : reader_(path), options_(std::move(options)) {
    if (options_.imagesDir.empty()) {
        options_.imagesDir = findImagesDirectory(path);
    }
    if (options_.reorderWindow == 0) options_.reorderWindow = 1;
    // MRPT resolves delay-loaded image paths against one process-wide base folder.
    mrpt::img::CImage::setImagesPathBase(options_.imagesDir);
}

CObservation::Ptr RawlogSource::next() {
    while (!input_done_ && window_.size() < options_.reorderWindow) {
        if (!readOneEntry()) {
            input_done_ = true;
            // Actions after the last observation: the motion ended no earlier than it.
            for (auto& odo : unstamped_) {
                odo->timestamp = latest_stamp_;
                push(std::move(odo));
            }
            unstamped_.clear();
        }
    }
    if (!window_.empty()) return pop();
    if (pending_error_) {
        auto error = pending_error_;
        pending_error_ = nullptr;
        std::rethrow_exception(error);
    }
    return nullptr;
}

bool RawlogSource::readOneEntry() {
    std::optional<RawlogEntry> entry;
    try {
        entry = reader_.next();
    } catch (const RawlogReadError&) {
        pending_error_ = std::current_exception();
        return false;
    }
    if (!entry) return false;
    ++entries_read_;
    const auto& object = *entry->object;
    format_ = updateFormat(format_, object);
    for (auto& obs : observationsOf(entry->object)) {
        if (!unstamped_.empty() && obs->timestamp != INVALID_TIMESTAMP) {
            // The motion of unstamped actions ended when the next frame was observed.
            for (auto& odo : unstamped_) {
                odo->timestamp = obs->timestamp;
                push(std::move(odo));
            }
            unstamped_.clear();
        }
        push(std::move(obs));
    }
    if (IS_CLASS(object, mrpt::obs::CActionCollection)) pushOdometryFromActions(object);
    return true;
}

void RawlogSource::pushOdometryFromActions(const mrpt::serialization::CSerializable& object) {
    const auto& actions = dynamic_cast<const mrpt::obs::CActionCollection&>(object);
    for (const auto& action : actions) {
        const auto* move = dynamic_cast<const mrpt::obs::CActionRobotMovement2D*>(action.get());
        if (!move || !move->poseChange) {
            ++skipped_actions_;
            continue;
        }
        odometry_pose_ = odometry_pose_ + move->poseChange->getMeanVal();
        auto odo = mrpt::obs::CObservationOdometry::Create();
        odo->timestamp = move->timestamp;
        odo->sensorLabel = options_.odometryLabel;
        odo->odometry = odometry_pose_;
        // MRPT leaves the flag unset when an old format version did not store it (MRPT's own
        // localization_demo.rawlog reads byte 8 there): anything but 0 / 1 means "unknown",
        // and ticks that may be garbage are not used. (Read as a byte: a bool holding 8 is
        // undefined behaviour.)
        std::uint8_t encodersFlag = 0;
        std::memcpy(&encodersFlag, &move->hasEncodersInfo, 1);
        if (encodersFlag > 1) ++unknown_encoder_flags_;
        if (encodersFlag == 1) {
            left_ticks_ += move->encoderLeftTicks;
            right_ticks_ += move->encoderRightTicks;
            odo->hasEncodersInfo = true;
            odo->encoderLeftTicks = static_cast<int32_t>(left_ticks_);
            odo->encoderRightTicks = static_cast<int32_t>(right_ticks_);
        }
        std::uint8_t velocitiesFlag = 0;
        std::memcpy(&velocitiesFlag, &move->hasVelocities, 1);
        if (velocitiesFlag == 1) {
            odo->hasVelocities = true;
            odo->velocityLocal = move->velocityLocal;
        }
        if (odo->timestamp == INVALID_TIMESTAMP) {
            unstamped_.push_back(std::move(odo));  // stamped by the next observation
        } else {
            push(odo);
        }
    }
}

void RawlogSource::push(CObservation::Ptr obs) {
    if (obs->timestamp != INVALID_TIMESTAMP && obs->timestamp > latest_stamp_) latest_stamp_ = obs->timestamp;
    window_.push(Pending{obs->timestamp, sequence_++, std::move(obs)});
}

CObservation::Ptr RawlogSource::pop() {
    Pending top = window_.top();
    window_.pop();
    if (released_any_ && top.stamp < last_released_) {
        ++out_of_order_;
    } else {
        last_released_ = top.stamp;
    }
    released_any_ = true;
    return top.obs;
}

}  // namespace lodestone::io
