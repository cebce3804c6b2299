package io.dtron.engine.coverage;

import java.util.ArrayList;
import java.util.List;
import java.util.Locale;

/**
 * When a run may end before its timeout: {@code --until EXPR}, with GraphWalker's names where they fit. An
 * expression combines, with {@code and}, {@code or} and parentheses ({@code and} binds tighter), the conditions
 * <ul>
 * <li>{@code edge_coverage(P)}: at least P percent of the coverable edges taken for certain;</li>
 * <li>{@code location_coverage(P)}: the same for locations;</li>
 * <li>{@code trap_coverage(P)}: at least P percent of the model's traps set for certain;</li>
 * <li>{@code reached(N)}: goal number N (the N-th {@code --goal}, from 1) reached;</li>
 * <li>{@code time(T)}: T model time units have passed since the start;</li>
 * <li>{@code inputs(N)}: N inputs applied.</li>
 * </ul>
 * The timeout stays the outer bound. Immutable.
 */
public final class StopCondition {
    private final String text;
    private final Node root;

    private StopCondition(String text, Node root) {
        this.text = text;
        this.root = root;
    }

    /** What a condition is evaluated on: the run so far. */
    public interface Context {
        /** The run's coverage so far. */
        RunCoverage coverage();

        /** The run's goals. */
        Goals goals();

        /** The test time so far, in model time units. */
        double time();

        /** The inputs applied so far. */
        int inputs();
    }

    /**
     * Parses {@code text}.
     *
     * @throws IllegalArgumentException with a one-line message naming the column (from 1) and what was expected
     */
    public static StopCondition parse(String text) {
        Parser p = new Parser(text);
        Node root = p.or();
        p.skipSpaces();
        if (p.pos < text.length()) {
            throw p.error("expected 'and', 'or' or the end, found '" + p.rest() + "'");
        }
        return new StopCondition(text, root);
    }

    /**
     * Checks the condition against the run's goals and traps before the run starts.
     *
     * @throws IllegalArgumentException naming the column of a {@code reached(N)} beyond the goals given, or of a
     *                                  {@code trap_coverage} on a model without traps
     */
    public void check(int goals, int traps) {
        for (Atom a : atoms()) {
            if (a.kind == Kind.REACHED && a.value > goals) {
                throw new IllegalArgumentException("column " + a.column + ": reached(" + (long) a.value + ") asks for"
                        + " goal " + (long) a.value + ", but the run has " + (goals == 0 ? "no goals (give them with"
                        + " --goal)" : goals == 1 ? "1 goal" : goals + " goals"));
            }
            if (a.kind == Kind.TRAP && traps == 0) {
                throw new IllegalArgumentException("column " + a.column + ": trap_coverage asks about traps, but the"
                        + " model has none (bool variables or arrays named trap... or t_..., or named with --traps)");
            }
        }
    }

    /** The expression as given. */
    @Override
    public String toString() {
        return text;
    }

    /**
     * Whether the condition holds: null when it does not, else which of its conditions made it hold, as written
     * ({@code location_coverage(100) and reached(1)}, or {@code time(90)} for the other branch of an {@code or}).
     */
    public String met(Context context) {
        return root.met(context);
    }

    /**
     * The earliest {@code time(T)} of the expression later than {@code units}, in model time units, or
     * {@link Long#MAX_VALUE}: when the tester must look at the condition again even if nothing happens.
     */
    public long nextTime(double units) {
        long next = Long.MAX_VALUE;
        for (Atom a : atoms()) {
            if (a.kind == Kind.TIME && a.value > units) {
                next = Math.min(next, (long) a.value);
            }
        }
        return next;
    }

    private List<Atom> atoms() {
        List<Atom> out = new ArrayList<>();
        root.atoms(out);
        return out;
    }

    private enum Kind {
        EDGE("edge_coverage"), LOCATION("location_coverage"), TRAP("trap_coverage"), REACHED("reached"),
        TIME("time"), INPUTS("inputs");

        final String word;

        Kind(String word) {
            this.word = word;
        }
    }

    private interface Node {
        String met(Context c);

        void atoms(List<Atom> out);
    }

    private record Or(List<Node> parts) implements Node {
        @Override
        public String met(Context c) {
            for (Node n : parts) {
                String m = n.met(c);
                if (m != null) {
                    return m;
                }
            }
            return null;
        }

        @Override
        public void atoms(List<Atom> out) {
            parts.forEach(n -> n.atoms(out));
        }
    }

    private record And(List<Node> parts) implements Node {
        @Override
        public String met(Context c) {
            List<String> all = new ArrayList<>();
            for (Node n : parts) {
                String m = n.met(c);
                if (m == null) {
                    return null;
                }
                all.add(n instanceof Or ? "(" + m + ")" : m);
            }
            return String.join(" and ", all);
        }

        @Override
        public void atoms(List<Atom> out) {
            parts.forEach(n -> n.atoms(out));
        }
    }

    private record Atom(Kind kind, double value, String written, int column) implements Node {
        @Override
        public String met(Context c) {
            boolean holds = switch (kind) {
                case EDGE -> c.coverage().edges().percent() >= value;
                case LOCATION -> c.coverage().locations().percent() >= value;
                case TRAP -> c.coverage().traps().percent() >= value;
                case REACHED -> c.goals().reached((int) value);
                case TIME -> c.time() >= value;
                case INPUTS -> c.inputs() >= value;
            };
            return holds ? written : null;
        }

        @Override
        public void atoms(List<Atom> out) {
            out.add(this);
        }
    }

    private static final class Parser {
        final String text;
        int pos;

        Parser(String text) {
            this.text = text;
        }

        Node or() {
            List<Node> parts = new ArrayList<>(List.of(and()));
            while (word("or")) {
                parts.add(and());
            }
            return parts.size() == 1 ? parts.get(0) : new Or(parts);
        }

        Node and() {
            List<Node> parts = new ArrayList<>(List.of(primary()));
            while (word("and")) {
                parts.add(primary());
            }
            return parts.size() == 1 ? parts.get(0) : new And(parts);
        }

        Node primary() {
            skipSpaces();
            if (pos < text.length() && text.charAt(pos) == '(') {
                pos++;
                Node inner = or();
                skipSpaces();
                expect(')');
                return inner;
            }
            int start = pos;
            while (pos < text.length() && (Character.isLetterOrDigit(text.charAt(pos)) || text.charAt(pos) == '_')) {
                pos++;
            }
            String name = text.substring(start, pos);
            if (name.isEmpty()) {
                pos = start;
                throw error(pos >= text.length() ? "expected a condition, found the end"
                        : "expected a condition, found '" + rest() + "'");
            }
            Kind kind = null;
            for (Kind k : Kind.values()) {
                if (k.word.equals(name.toLowerCase(Locale.ROOT))) {
                    kind = k;
                }
            }
            if (kind == null) {
                pos = start;
                throw error("unknown condition '" + name + "': use edge_coverage(P), location_coverage(P),"
                        + " trap_coverage(P), reached(N), time(T) or inputs(N)");
            }
            skipSpaces();
            expect('(');
            skipSpaces();
            int numberAt = pos;
            while (pos < text.length() && (Character.isDigit(text.charAt(pos)) || text.charAt(pos) == '.')) {
                pos++;
            }
            String number = text.substring(numberAt, pos);
            double value;
            try {
                value = Double.parseDouble(number);
            } catch (NumberFormatException e) {
                pos = numberAt;
                throw error("expected a number in " + name + "(...)");
            }
            boolean percent = kind == Kind.EDGE || kind == Kind.LOCATION || kind == Kind.TRAP;
            if (percent && value > 100) {
                pos = numberAt;
                throw error(name + " takes a percentage from 0 to 100, not " + number);
            }
            if (!percent && (number.contains(".") || kind == Kind.REACHED && value < 1)) {
                pos = numberAt;
                throw error(name + " takes a whole number" + (kind == Kind.REACHED ? " from 1" : "") + ", not "
                        + number);
            }
            skipSpaces();
            expect(')');
            return new Atom(kind, value, kind.word + "(" + number + ")", start + 1);
        }

        boolean word(String w) {
            skipSpaces();
            int end = pos + w.length();
            if (text.regionMatches(true, pos, w, 0, w.length())
                    && (end == text.length() || !Character.isLetterOrDigit(text.charAt(end)) && text.charAt(end) != '_')) {
                pos = end;
                return true;
            }
            return false;
        }

        void expect(char c) {
            if (pos >= text.length() || text.charAt(pos) != c) {
                throw error("expected '" + c + "', found " + (pos >= text.length() ? "the end" : "'" + rest() + "'"));
            }
            pos++;
        }

        void skipSpaces() {
            while (pos < text.length() && Character.isWhitespace(text.charAt(pos))) {
                pos++;
            }
        }

        String rest() {
            String r = text.substring(pos);
            return r.length() > 20 ? r.substring(0, 20) + "..." : r;
        }

        IllegalArgumentException error(String message) {
            return new IllegalArgumentException("column " + (pos + 1) + ": " + message);
        }
    }
}
