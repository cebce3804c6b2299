package io.dtron.model.internal;

import io.dtron.model.Type;
import java.util.List;
import java.util.Map;

/**
 * Uppaal's built-in functions that DTRON type-checks but its engine does not evaluate: the mathematical
 * functions on {@code double} and the random distributions of statistical model checking, {@code fint}, and
 * {@code abs}. A model that calls one loads, and its runs are refused.
 */
final class Builtins {
    private static final Type D = Type.Double.INSTANCE;
    private static final Type I = Type.Int.UNBOUNDED;
    private static final Type B = Type.Bool.INSTANCE;

    /** A built-in function's parameter types and return type. */
    record Signature(List<Type> parameters, Type returns) {
    }

    private static final Map<String, Signature> TABLE = Map.ofEntries(
            Map.entry("abs", new Signature(List.of(I), I)),
            Map.entry("fint", new Signature(List.of(D), I)),
            Map.entry("ilogb", new Signature(List.of(D), I)),
            Map.entry("signbit", new Signature(List.of(D), B)),
            Map.entry("ldexp", new Signature(List.of(D, I), D)),
            Map.entry("random", new Signature(List.of(D), D)),
            Map.entry("random_normal", new Signature(List.of(D, D), D)),
            Map.entry("random_poisson", new Signature(List.of(D), D)),
            Map.entry("random_arcsine", new Signature(List.of(D, D), D)),
            Map.entry("random_beta", new Signature(List.of(D, D), D)),
            Map.entry("random_gamma", new Signature(List.of(D, D), D)),
            Map.entry("random_tri", new Signature(List.of(D, D, D), D)),
            Map.entry("random_weibull", new Signature(List.of(D, D), D)),
            Map.entry("fma", new Signature(List.of(D, D, D), D)),
            entry2("fmod"), entry2("fmax"), entry2("fmin"), entry2("fdim"), entry2("pow"), entry2("hypot"),
            entry2("atan2"), entry2("nextafter"), entry2("copysign"),
            entry1("fabs"), entry1("exp"), entry1("exp2"), entry1("expm1"), entry1("ln"), entry1("log"),
            entry1("log10"), entry1("log2"), entry1("log1p"), entry1("sqrt"), entry1("cbrt"), entry1("sin"),
            entry1("cos"), entry1("tan"), entry1("asin"), entry1("acos"), entry1("atan"), entry1("sinh"),
            entry1("cosh"), entry1("tanh"), entry1("asinh"), entry1("acosh"), entry1("atanh"), entry1("erf"),
            entry1("erfc"), entry1("tgamma"), entry1("lgamma"), entry1("ceil"), entry1("floor"), entry1("trunc"),
            entry1("round"), entry1("logb"));

    private Builtins() {
    }

    private static Map.Entry<String, Signature> entry1(String name) {
        return Map.entry(name, new Signature(List.of(D), D));
    }

    private static Map.Entry<String, Signature> entry2(String name) {
        return Map.entry(name, new Signature(List.of(D, D), D));
    }

    /** The signature of the built-in function {@code name}, or null when there is none. */
    static Signature of(String name) {
        return TABLE.get(name);
    }
}
