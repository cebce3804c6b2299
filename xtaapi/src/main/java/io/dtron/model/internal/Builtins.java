package io.dtron.model.internal;

import io.dtron.model.Expression;
import io.dtron.model.Type;
import java.util.LinkedHashMap;
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

    /**
     * The constants and types Uppaal 5 declares for every model: the limits of the integer types with their
     * typedefs ({@code INT8_MIN} ... {@code INT32_MAX}, {@code int8_t} ... {@code int32_t}), the limits of
     * {@code float} and {@code double}, and the mathematical constants of C ({@code M_PI}, {@code M_PI_2},
     * {@code M_PI_4}, {@code M_E}, {@code M_LOG2E}, {@code M_LOG10E}, {@code M_LN2}, {@code M_LN10},
     * {@code M_1_PI}, {@code M_2_PI}, {@code M_2_SQRTPI}, {@code M_SQRT2}, {@code M_SQRT1_2}). They live in a scope
     * around the global one, so that a model that declares a name of its own (as models written before Uppaal 5
     * do) uses its own.
     */
    static Scope scope() {
        Scope scope = new Scope(null);
        Map<String, Integer> ints = new LinkedHashMap<>();
        ints.put("INT8_MIN", -128);
        ints.put("INT8_MAX", 127);
        ints.put("UINT8_MAX", 255);
        ints.put("INT16_MIN", -32768);
        ints.put("INT16_MAX", 32767);
        ints.put("UINT16_MAX", 65535);
        ints.put("INT32_MIN", Integer.MIN_VALUE);
        ints.put("INT32_MAX", Integer.MAX_VALUE);
        ints.forEach((name, value) -> scope.put(name, new Symbol.Constant(null, Type.Int.UNBOUNDED, new int[] {value})));
        scope.put("int8_t", new Symbol.TypeName(null, new Type.Int(-128, 127), false));
        scope.put("uint8_t", new Symbol.TypeName(null, new Type.Int(0, 255), false));
        scope.put("int16_t", new Symbol.TypeName(null, new Type.Int(-32768, 32767), false));
        scope.put("uint16_t", new Symbol.TypeName(null, new Type.Int(0, 65535), false));
        scope.put("int32_t", new Symbol.TypeName(null, new Type.Int(Integer.MIN_VALUE, Integer.MAX_VALUE), false));
        Map<String, Double> doubles = new LinkedHashMap<>();
        doubles.put("FLT_MIN", (double) Float.MIN_NORMAL);
        doubles.put("FLT_MAX", (double) Float.MAX_VALUE);
        doubles.put("DBL_MIN", Double.MIN_NORMAL);
        doubles.put("DBL_MAX", Double.MAX_VALUE);
        doubles.put("M_PI", Math.PI);
        doubles.put("M_PI_2", Math.PI / 2);
        doubles.put("M_PI_4", Math.PI / 4);
        doubles.put("M_E", Math.E);
        doubles.put("M_LOG2E", 1 / Math.log(2));
        doubles.put("M_LOG10E", 1 / Math.log(10));
        doubles.put("M_LN2", Math.log(2));
        doubles.put("M_LN10", Math.log(10));
        doubles.put("M_1_PI", 1 / Math.PI);
        doubles.put("M_2_PI", 2 / Math.PI);
        doubles.put("M_2_SQRTPI", 2 / Math.sqrt(Math.PI));
        doubles.put("M_SQRT2", Math.sqrt(2));
        doubles.put("M_SQRT1_2", Math.sqrt(0.5));
        doubles.forEach((name, value) -> scope.put(name, new Symbol.Alias(null,
                new Expression.DoubleConstant(null, Type.Double.INSTANCE, value), false, false, false)));
        return scope;
    }

    /** The signature of the built-in function {@code name}, or null when there is none. */
    static Signature of(String name) {
        return TABLE.get(name);
    }
}
