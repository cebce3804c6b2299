package io.dtron.xta.ast;

import io.dtron.xta.Pos;
import java.util.List;
import java.util.Set;

/** A type as written in the model, with its prefixes ({@code const}, {@code urgent}, ...). */
public sealed interface TypeExpr {

    /** Where the type was written. */
    Pos pos();

    /** The prefixes written before the type. */
    Set<Qualifier> qualifiers();

    /** A type prefix. */
    enum Qualifier { CONST, URGENT, BROADCAST, META, HYBRID }

    /** The built-in types without arguments. */
    enum Primitive { BOOL, CLOCK, CHAN, DOUBLE, VOID }

    /** {@code int} or {@code int[lower,upper]}; both bounds null for the default range. */
    record IntType(Pos pos, Set<Qualifier> qualifiers, Expr lower, Expr upper) implements TypeExpr {
        public IntType {
            qualifiers = Set.copyOf(qualifiers);
        }
    }

    /** {@code bool}, {@code clock}, {@code chan}, {@code double} or {@code void}. */
    record PrimitiveType(Pos pos, Set<Qualifier> qualifiers, Primitive primitive) implements TypeExpr {
        public PrimitiveType {
            qualifiers = Set.copyOf(qualifiers);
        }
    }

    /** {@code scalar[size]}. */
    record ScalarType(Pos pos, Set<Qualifier> qualifiers, Expr size) implements TypeExpr {
        public ScalarType {
            qualifiers = Set.copyOf(qualifiers);
        }
    }

    /** {@code struct { fields }}. */
    record StructType(Pos pos, Set<Qualifier> qualifiers, List<Field> fields) implements TypeExpr {
        public StructType {
            qualifiers = Set.copyOf(qualifiers);
            fields = List.copyOf(fields);
        }
    }

    /** A field of a struct type. */
    record Field(Pos pos, TypeExpr type, String name, List<ArrayDim> dims) {
        public Field {
            dims = List.copyOf(dims);
        }
    }

    /** A type named by a {@code typedef}. */
    record NamedType(Pos pos, Set<Qualifier> qualifiers, String name) implements TypeExpr {
        public NamedType {
            qualifiers = Set.copyOf(qualifiers);
        }
    }
}
