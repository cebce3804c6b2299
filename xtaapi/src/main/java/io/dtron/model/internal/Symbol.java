package io.dtron.model.internal;

import io.dtron.model.ChannelVariable;
import io.dtron.model.ClockVariable;
import io.dtron.model.Expression;
import io.dtron.model.Type;
import io.dtron.model.Variable;
import io.dtron.xta.Pos;
import io.dtron.xta.ast.Decl;
import java.util.List;

/** What a name stands for in a scope. */
sealed interface Symbol {

    /** Where the name was declared. */
    Pos pos();

    /** A type name; {@code constant} when the typedef carries {@code const}. */
    record TypeName(Pos pos, Type type, boolean constant) implements Symbol {
    }

    /** A compile-time constant (scalars in values[0]; arrays and structs laid out flat). */
    record Constant(Pos pos, Type type, int[] values) implements Symbol {
    }

    /** A variable of the state vector. */
    record Var(Pos pos, Variable variable) implements Symbol {
    }

    /** A clock or clock array. */
    record ClockVar(Pos pos, ClockVariable clock) implements Symbol {
    }

    /** A channel or channel array. */
    record ChanVar(Pos pos, ChannelVariable channel) implements Symbol {
    }

    /** A frame slot: a function parameter or local, a select binding, a quantified name. */
    record Local(Pos pos, Type type, int slot, boolean reference, boolean assignable) implements Symbol {
    }

    /** A function; its signature is known before its body is compiled. */
    record Func(Pos pos, FunctionInfo info) implements Symbol {
    }

    /**
     * An external function of an {@code import} block: type-checked, never evaluated.
     *
     * @param references for each parameter, whether it is a reference
     */
    record External(Pos pos, String name, Type returnType, List<Type> parameters, List<Boolean> references,
                    String library) implements Symbol {
        public External {
            parameters = List.copyOf(parameters);
            references = List.copyOf(references);
        }
    }

    /** A template. */
    record Template(Pos pos, Decl.Template decl) implements Symbol {
    }

    /** An instantiation, possibly partial. */
    record Instantiation(Pos pos, Decl.Instantiation decl) implements Symbol {
    }

    /**
     * A parameter that the system line enumerates: a constant in each process, but not assignable and, unless
     * declared {@code const}, not computable at compile time for Uppaal's instantiation rules.
     */
    record FreeParam(Pos pos, Type type, int value, boolean declaredConst, String owner) implements Symbol {
    }

    /**
     * A parameter bound to an expression: a reference parameter bound to its argument, a channel passed by
     * value, a {@code const} parameter whose argument is not a constant, or a placeholder while a template is
     * checked without being instantiated.
     */
    record Alias(Pos pos, Expression target, boolean assignable, boolean placeholder, boolean reference)
            implements Symbol {
    }
}
