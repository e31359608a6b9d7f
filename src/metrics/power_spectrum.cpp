#include "metrics/power_spectrum.h"

#include <fftw3.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
#include <stdexcept>

namespace pathlab {
namespace {

// FFTW's planner keeps global state and is not thread-safe (FFTW manual,
// "Thread safety"); executing a plan is. Plans are made and destroyed under
// this lock, executed outside it.
std::mutex& fftwPlannerMutex() {
    static std::mutex mutex;
    return mutex;
}

// A real-to-complex 2-D transform of a width × height image: the input, the
// h × (w/2 + 1) half of its Hermitian-symmetric spectrum, and the plan.
class RealFft2d {
  public:
    RealFft2d(int width, int height)
        : in_(fftw_alloc_real(size_t(width) * size_t(height))),
          out_(fftw_alloc_complex(size_t(width / 2 + 1) * size_t(height))) {
        if (!in_ || !out_) {
            release();
            throw std::bad_alloc();
        }
        std::lock_guard<std::mutex> lock(fftwPlannerMutex());
        // FFTW_ESTIMATE chooses by heuristics, never by timing: the same plan,
        // hence the same bits, on every run. Row-major: height rows of width.
        plan_ = fftw_plan_dft_r2c_2d(height, width, in_, out_, FFTW_ESTIMATE);
        if (!plan_) {
            fftw_free(in_), fftw_free(out_);
            throw std::runtime_error("FFTW could not plan a " + std::to_string(width) + "x" +
                                     std::to_string(height) + " transform");
        }
    }
    ~RealFft2d() { release(); }
    RealFft2d(const RealFft2d&) = delete;
    RealFft2d& operator=(const RealFft2d&) = delete;

    double* input() { return in_; }
    const fftw_complex* output() const { return out_; }
    void execute() { fftw_execute(plan_); }

  private:
    void release() {
        if (plan_) {
            std::lock_guard<std::mutex> lock(fftwPlannerMutex());
            fftw_destroy_plan(plan_);
            plan_ = nullptr;
        }
        fftw_free(in_), fftw_free(out_);
        in_ = nullptr, out_ = nullptr;
    }

    double* in_;
    fftw_complex* out_;
    fftw_plan plan_ = nullptr;
};

// Accumulates P(k) into rings and totals (see RadialPowerSpectrum).
class RingAccumulator {
  public:
    RingAccumulator(int width, int height)
        : w_(width),
          h_(height),
          n_(std::min(width, height)),
          sum_(size_t(n_ / 2) + 1, 0.0),
          count_(sum_.size(), 0) {}

    // Frequency (kx, ky), ky signed, of periodogram value p, standing for
    // `multiplicity` frequencies of the full plane (itself and its mirror −k).
    void add(int kx, int ky, double p, int multiplicity) {
        const double weighted = p * multiplicity;
        if (kx == 0 && ky == 0) {
            dc_ = p;
            return;
        }
        total_ += weighted;
        // |f| < 1/8 in integers, exactly: 64·(kx²h² + ky²w²) < w²h².
        const int64_t w = w_, h = h_;
        if (64 * (int64_t(kx) * kx * h * h + int64_t(ky) * ky * w * w) < w * w * h * h)
            low_ += weighted;
        const double fx = double(kx) / w_, fy = double(ky) / h_;
        const long ring = std::max(1L, std::lround(n_ * std::sqrt(fx * fx + fy * fy)));
        if (ring >= long(sum_.size())) return;
        sum_[size_t(ring)] += weighted;
        count_[size_t(ring)] += multiplicity;
    }

    RadialPowerSpectrum finish() const {
        RadialPowerSpectrum s;
        const double pixels = double(w_) * double(h_);
        s.frequency.resize(sum_.size());
        s.power.resize(sum_.size());
        s.count = count_;
        s.count[0] = 1;
        s.power[0] = dc_;
        for (size_t r = 0; r < sum_.size(); ++r) {
            s.frequency[r] = double(r) / n_;
            if (r > 0) s.power[r] = count_[r] ? sum_[r] / double(count_[r]) : 0.0;
        }
        s.totalPower = total_ / pixels;
        s.lowFrequencyPower = low_ / pixels;
        return s;
    }

  private:
    int w_, h_, n_;
    std::vector<double> sum_;
    std::vector<int64_t> count_;
    double dc_ = 0, total_ = 0, low_ = 0;
};

}  // namespace

double RadialPowerSpectrum::lowFrequencyFraction() const {
    if (!(totalPower > 0)) return std::numeric_limits<double>::quiet_NaN();
    return lowFrequencyPower / totalPower;
}

RadialPowerSpectrum radialPeriodogram(const std::vector<double>& values, int width, int height) {
    if (width < 1 || height < 1 || values.size() != size_t(width) * size_t(height))
        throw std::invalid_argument("radialPeriodogram: values do not match the size");
    RealFft2d fft(width, height);
    std::copy(values.begin(), values.end(), fft.input());
    fft.execute();
    const double pixels = double(width) * double(height);
    const int halfWidth = width / 2 + 1;
    RingAccumulator rings(width, height);
    for (int y = 0; y < height; ++y) {
        const int ky = y <= height / 2 ? y : y - height;
        for (int kx = 0; kx < halfWidth; ++kx) {
            const fftw_complex& c = fft.output()[size_t(y) * halfWidth + kx];
            const double p = (c[0] * c[0] + c[1] * c[1]) / pixels;
            // Columns 1..⌈w/2⌉−1 stand for their mirrors w−kx too (a real
            // image's spectrum is Hermitian); column 0 and, for even w, column
            // w/2 are their own mirrors' columns and are stored whole.
            const bool ownMirror = kx == 0 || 2 * kx == width;
            rings.add(kx, ky, p, ownMirror ? 1 : 2);
        }
    }
    return rings.finish();
}

}  // namespace pathlab
