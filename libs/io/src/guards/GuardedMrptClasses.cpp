// Stock deserializers that crash on a damaged file, inside MRPT, where no exception handler
// can help (found by tests/fuzz/fuzz_rawlog):
// - CActionCollection stores each action read into a deep-copying pointer, which clones it:
//   an action stored as "nullptr" is dereferenced.
// - CActionRobotMovement2D reads its pose PDF as an object pointer; stored as "nullptr" or as
//   an object of another class, it is null, and MRPT dereferences it (getMean() in versions
//   0-1, the deep-copying assignment in later ones).
//
// The guards are subclasses that read the risky part themselves and throw on what MRPT would
// dereference. The collection reads its count and its actions one at a time (nothing is
// allocated from the count) and inserts each, which clones it into a stock object. The
// movement reads its leading fields and PDF, checks them, and hands MRPT's own deserializer
// the same bytes followed by the rest of the stream (PrefixedArchive), so the format stays
// MRPT's. Both are registered in MRPT's class registry under the stock names, which is how
// CArchive::ReadObject finds what to create, and report the stock class as their runtime
// class: IS_CLASS, class names and re-serialization see the stock classes.
#include "GuardedMrptClasses.h"

#include "BudgetedMatAllocator.h"

#include <mrpt/io/CMemoryStream.h>
#include <mrpt/maps/registerAllClasses.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/poses/CPosePDF.h>
#include <mrpt/rtti/CObject.h>
#include <mrpt/serialization/CArchive.h>

#include <algorithm>
#include <cstring>
#include <iostream>
#include <mutex>
#include <sstream>
#include <stdexcept>

namespace lodestone::io::detail {
namespace {

using mrpt::obs::CActionRobotMovement2D;

/** Reads `prefix` first, then whatever follows in `rest`: lets MRPT's own deserializer read
 * an object whose leading part a guard has already read and checked. */
class PrefixedArchive : public mrpt::serialization::CArchive {
  public:
    PrefixedArchive(std::string prefix, mrpt::serialization::CArchive& rest)
        : prefix_(std::move(prefix)), rest_(rest) {}

  protected:
    size_t write(const void*, size_t) override {
        throw std::logic_error("PrefixedArchive is read-only");
    }
    size_t read(void* buf, size_t len) override {
        const std::size_t fromPrefix = std::min(len, prefix_.size() - used_);
        std::memcpy(buf, prefix_.data() + used_, fromPrefix);
        used_ += fromPrefix;
        if (fromPrefix == len) return len;
        return fromPrefix + rest_.ReadBuffer(static_cast<char*>(buf) + fromPrefix, len - fromPrefix);
    }

  private:
    std::string prefix_;
    std::size_t used_{0};
    mrpt::serialization::CArchive& rest_;
};

std::string serializedBytes(const mrpt::serialization::CSerializable& object) {
    mrpt::io::CMemoryStream buffer;
    auto out = mrpt::serialization::archiveFrom(buffer);
    out << object;
    return std::string(static_cast<const char*>(buffer.getRawBufferData()), buffer.getTotalBytesCount());
}

class GuardedRobotMovement2D : public CActionRobotMovement2D {
  public:
    const mrpt::rtti::TRuntimeClassId* GetRuntimeClass() const override {
        return &CActionRobotMovement2D::GetRuntimeClassIdStatic();
    }

  protected:
    // Versions 0-1 start with the PDF; later ones with the estimation method, then the PDF
    // unless the method is odometry (whose PDF MRPT rebuilds from the increment it reads).
    void serializeFrom(mrpt::serialization::CArchive& in, uint8_t version) override {
        std::string checked;
        if (version >= 2) {
            std::int32_t method = 0;
            in >> method;
            checked.assign(reinterpret_cast<const char*>(&method), sizeof(method));
            if (method == emOdometry) {
                PrefixedArchive again(checked, in);
                CActionRobotMovement2D::serializeFrom(again, version);
                return;
            }
        }
        const auto pdf = in.ReadObject<mrpt::poses::CPosePDF>();
        if (!pdf) {
            // (The reader's message names the class already: "... > CActionRobotMovement2D: ".)
            throw std::runtime_error("version " + std::to_string(version) +
                                     ": the pose PDF is missing or not a CPosePDF");
        }
        checked += serializedBytes(*pdf);
        PrefixedArchive again(checked, in);
        CActionRobotMovement2D::serializeFrom(again, version);
    }
};

class GuardedActionCollection : public mrpt::obs::CActionCollection {
  public:
    const mrpt::rtti::TRuntimeClassId* GetRuntimeClass() const override {
        return &CActionCollection::GetRuntimeClassIdStatic();
    }

  protected:
    void serializeFrom(mrpt::serialization::CArchive& in, uint8_t version) override {
        if (version != 0) {
            CActionCollection::serializeFrom(in, version);  // MRPT's verdict on the version
            return;
        }
        std::uint32_t count = 0;
        in >> count;
        clear();
        for (std::uint32_t k = 0; k < count; ++k) {
            const auto action = in.ReadObject<mrpt::obs::CAction>();
            if (!action) {
                throw std::runtime_error("action " + std::to_string(k) + " is null or not a CAction");
            }
            insert(*action);  // a copy of the stock class (clone), as MRPT stores it
        }
    }
};

const mrpt::rtti::TRuntimeClassId* actionBaseClass() {
    return &mrpt::obs::CAction::GetRuntimeClassIdStatic();
}
const mrpt::rtti::TRuntimeClassId* serializableBaseClass() {
    return &mrpt::serialization::CSerializable::GetRuntimeClassIdStatic();
}

const mrpt::rtti::TRuntimeClassId kGuardedRobotMovement2D{
    CActionRobotMovement2D::className,
    [] { return std::shared_ptr<mrpt::rtti::CObject>(std::make_shared<GuardedRobotMovement2D>()); },
    &actionBaseClass};

const mrpt::rtti::TRuntimeClassId kGuardedActionCollection{
    mrpt::obs::CActionCollection::className,
    [] { return std::shared_ptr<mrpt::rtti::CObject>(std::make_shared<GuardedActionCollection>()); },
    &serializableBaseClass};

}  // namespace

void installGuardedMrptClasses() {
    static std::once_flag once;
    std::call_once(once, [] {
        // Observations MRPT defines in mrpt-maps (CObservationRotatingScan, point-cloud
        // observations) are stock rawlog classes too; MRPT registers its classes lazily, and
        // ours must come after the stock ones.
        mrpt::maps::registerAllClasses_mrpt_maps();
        mrpt::rtti::registerAllPendingClasses();
        // The registry warns on std::cerr that a name is overwritten: that is the point here.
        std::ostringstream quiet;
        auto* previous = std::cerr.rdbuf(quiet.rdbuf());
        mrpt::rtti::registerClass(&kGuardedRobotMovement2D);
        mrpt::rtti::registerClass(&kGuardedActionCollection);
        std::cerr.rdbuf(previous);
        installBudgetedMatAllocator();
    });
}

}  // namespace lodestone::io::detail
