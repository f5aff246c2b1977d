// A plugin module for lodestone-grab's tests: CFailingSensor emits a comment observation per
// doProcess() and throws on the `fail_after`-th call - a sensor that dies while grabbing.
#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/core/initializer.h>
#include <mrpt/hwdrivers/CGenericSensor.h>
#include <mrpt/obs/CObservationComment.h>

#include <stdexcept>

namespace lodestone::test {

class CFailingSensor : public mrpt::hwdrivers::CGenericSensor {
    DEFINE_GENERIC_SENSOR(CFailingSensor)

  public:
    void doProcess() override {
        if (++calls_ >= fail_after_) throw std::runtime_error("the test sensor's cable came out");
        auto c = mrpt::obs::CObservationComment::Create();
        c->timestamp = mrpt::Clock::now();
        c->sensorLabel = m_sensorLabel;
        c->text = "call " + std::to_string(calls_);
        appendObservation(c);
    }

  protected:
    void loadConfig_sensorSpecific(const mrpt::config::CConfigFileBase& c,
                                   const std::string& section) override {
        fail_after_ = c.read_int(section, "fail_after", 10);
    }

  private:
    int calls_{0}, fail_after_{10};
};

}  // namespace lodestone::test

IMPLEMENTS_GENERIC_SENSOR(CFailingSensor, lodestone::test)

MRPT_INITIALIZER(lodestone_test_failing_sensor) { lodestone::test::CFailingSensor::doRegister(); }
