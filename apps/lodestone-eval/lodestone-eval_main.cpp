// lodestone-eval: ATE / RPE of a TUM trajectory against ground truth, with a plot.
#include <EvalApp.h>

#include <iostream>

int main(int argc, char** argv) {
    return lodestone::eval::runEvalApp(argc, argv, std::cout, std::cerr);
}
