#include <lodestone/magnetic/DistanceResampler.h>

#include <cmath>
#include <stdexcept>

namespace lodestone::magnetic {

DistanceResampler::DistanceResampler(double step) : step_(step) {
    if (!(step > 0)) throw std::invalid_argument("DistanceResampler: step must be > 0");
}

void DistanceResampler::reset() {
    bin_.reset();
    last_.reset();
    count_ = 0;
}

std::vector<DistanceResampler::Sample> DistanceResampler::add(double s,
                                                              const Eigen::VectorXd& value) {
    std::vector<Sample> out;
    const long bin = static_cast<long>(std::floor(s / step_));
    if (bin_ && bin < *bin_) return out;  // travel never goes back; ignore a stray reading
    if (bin_ && bin != *bin_ && count_ > 0) {
        Sample done{(*bin_ + 0.5) * step_, sum_ / count_};
        // Bins skipped between the last emitted one and this one: interpolate.
        if (last_) {
            const long from = static_cast<long>(std::floor(last_->s / step_));
            for (long k = from + 1; k < *bin_; ++k) {
                const double f = double(k - from) / double(*bin_ - from);
                out.push_back({(k + 0.5) * step_, last_->value + f * (done.value - last_->value)});
            }
        }
        out.push_back(done);
        last_ = done;
        count_ = 0;
    }
    if (!bin_ || bin != *bin_ || count_ == 0) {
        bin_ = bin;
        sum_ = Eigen::VectorXd::Zero(value.size());
    }
    sum_ += value;
    ++count_;
    return out;
}

}  // namespace lodestone::magnetic
