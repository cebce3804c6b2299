package io.dtron.model.internal;

import io.dtron.model.ChannelVariable;
import io.dtron.model.Edge;
import io.dtron.model.Expression;
import io.dtron.model.Location;
import io.dtron.model.Network;
import io.dtron.model.Process;
import io.dtron.model.TestInterface;
import io.dtron.model.TestInterface.ObservableChannel;
import io.dtron.model.Type;
import io.dtron.model.delta.DeltaExtension.Change;
import io.dtron.model.delta.DeltaExtension.Delay;
import io.dtron.model.delta.DeltaExtension.Left;
import io.dtron.model.delta.DeltaExtension.Result;
import io.dtron.xta.Fragment;
import io.dtron.xta.ModelSyntax;
import io.dtron.xta.Pos;
import java.util.ArrayList;
import java.util.HashMap;
import java.util.LinkedHashSet;
import java.util.List;
import java.util.Map;
import java.util.Set;
import java.util.TreeMap;
import java.util.regex.Pattern;

/**
 * The work of {@link io.dtron.model.delta.DeltaExtension#extend}: finds the clock bounds of the observable edges
 * and of their source locations' invariants, merges what the processes of one template ask of their shared label
 * text (lower bounds by the least widening, upper bounds by the largest), and edits the text in place.
 */
public final class DeltaWidener {
    private static final Pattern ATOM = Pattern.compile("[A-Za-z_][A-Za-z0-9_]*|[0-9]+");
    private static final int MAX_LISTED = 20;

    private final Network network;
    private final String text;
    private final TestInterface testInterface;
    private final Map<String, Delay> delays;
    private final long unit;
    private final String source;
    private final boolean xml;
    private final Map<Integer, ObservableChannel> inputs = new HashMap<>();
    private final Map<Integer, ObservableChannel> outputs = new HashMap<>();
    private final Delay inputHull;
    private final Delay outputHull;
    /** The comparisons of observable edges and invariants, by their start offset in the file. */
    private final Map<Integer, Bound> bounds = new TreeMap<>();
    /** Every process whose guards or invariants hold a comparison, by the comparison's start offset in the file. */
    private final Map<Integer, Set<String>> users = new HashMap<>();

    /** Widening of one edge, in microseconds: the least of its lower sums and the largest of its upper sums. */
    private record Amount(long lowMicros, long highMicros, String channels) {
    }

    private enum Kind { LOWER, UPPER, EQUAL }

    /** A clock comparison of an observable edge or invariant, with what every process using it asks of it. */
    private static final class Bound {
        final Expression.Binary comparison;
        final String template;
        final String place;
        final Set<String> channels = new LinkedHashSet<>();
        final Set<String> processes = new LinkedHashSet<>();
        Kind kind;
        Expression clock;
        Expression bound;
        String leftReason;
        long lowMicros = Long.MAX_VALUE;
        long highMicros = Long.MIN_VALUE;

        Bound(Expression.Binary comparison, String template, String place) {
            this.comparison = comparison;
            this.template = template;
            this.place = place;
        }
    }

    /** An edit of the file: the characters {@code start..end} replaced by {@code raw}. */
    private record Edit(int start, int end, String raw) {
    }

    /** Prepares the widening; see {@link io.dtron.model.delta.DeltaExtension#extend} for the arguments. */
    public DeltaWidener(Network network, String text, TestInterface testInterface, Map<String, Delay> delays,
                        long timeUnitMicros, String source) {
        if (timeUnitMicros <= 0) {
            throw new IllegalArgumentException("the time unit must be a positive number of microseconds, not "
                    + timeUnitMicros);
        }
        if (delays.isEmpty()) {
            throw new IllegalArgumentException("no delays given: name at least one channel with its interval");
        }
        this.network = network;
        this.text = text;
        this.testInterface = testInterface;
        this.delays = Map.copyOf(delays);
        this.unit = timeUnitMicros;
        this.source = source;
        this.xml = ModelSyntax.isXml(text);
        for (ObservableChannel c : testInterface.inputs()) {
            inputs.put(checked(c), c);
        }
        for (ObservableChannel c : testInterface.outputs()) {
            outputs.put(checked(c), c);
        }
        Delay in = null;
        Delay out = null;
        for (Map.Entry<String, Delay> e : this.delays.entrySet()) {
            boolean input = testInterface.input(e.getKey()).isPresent();
            if (!input && testInterface.output(e.getKey()).isEmpty()) {
                throw new IllegalArgumentException("'" + e.getKey() + "' is no channel of the test interface ("
                        + describeInterface() + ")");
            }
            if (input) {
                in = in == null ? e.getValue() : in.hull(e.getValue());
            } else {
                out = out == null ? e.getValue() : out.hull(e.getValue());
            }
        }
        this.inputHull = in;
        this.outputHull = out;
    }

    private int checked(ObservableChannel c) {
        if (c.channel() < 0 || c.channel() >= network.channelCount()
                || !network.channelName(c.channel()).equals(c.modelName())) {
            throw new IllegalArgumentException("the test interface was not made for " + network.file() + ": it has no"
                    + " channel " + c.modelName() + " at number " + c.channel());
        }
        return c.channel();
    }

    private String describeInterface() {
        String in = String.join(", ", testInterface.inputs().stream().map(ObservableChannel::name).toList());
        String out = String.join(", ", testInterface.outputs().stream().map(ObservableChannel::name).toList());
        return "inputs: " + (in.isEmpty() ? "none" : in) + "; outputs: " + (out.isEmpty() ? "none" : out);
    }

    /** Finds the bounds, edits the text and writes the comment. */
    public Result widen() {
        for (Process p : network.processes()) {
            for (Location l : p.locations()) {
                recordUsers(l.invariant(), p);
            }
            for (Edge e : p.edges()) {
                recordUsers(e.guard(), p);
            }
        }
        for (Process p : network.processes()) {
            for (Edge e : p.edges()) {
                Amount amount = e.sync() == null ? null : amount(e.sync());
                if (amount == null) {
                    continue;
                }
                Location from = p.locations().get(e.source());
                String edge = p.template() + ": edge " + from.name() + " -> " + p.locations().get(e.target()).name();
                visit(e.guard(), false, p, amount, edge + ", guard");
                visit(from.invariant(), true, p, amount, p.template() + ": location " + from.name() + ", invariant");
            }
        }
        List<Edit> edits = new ArrayList<>();
        List<Change> changes = new ArrayList<>();
        List<Left> left = new ArrayList<>();
        List<String> warnings = new ArrayList<>();
        for (Bound b : bounds.values()) {
            String place = "line " + b.comparison.pos().line() + ", " + b.place + " (" + String.join(", ", b.channels)
                    + ")";
            String before = oneLine(b.comparison.pos().text());
            String reason = b.leftReason != null ? b.leftReason : roundingReason(b);
            if (reason != null) {
                left.add(new Left(place, before, reason));
                continue;
            }
            changes.add(new Change(place, before, oneLine(edit(b, edits))));
            Set<String> others = new LinkedHashSet<>(users.getOrDefault(b.comparison.pos().fragment()
                    .fileOffset(b.comparison.pos().start()), Set.of()));
            others.removeAll(b.processes);
            if (!others.isEmpty()) {
                warnings.add(place + ": '" + before + "' is widened for every process of template " + b.template
                        + ", also for " + String.join(", ", others) + ", where it belongs to no edge of an input or"
                        + " output");
            }
        }
        edits.add(note(changes, left));
        return new Result(apply(edits), changes, left, warnings);
    }

    // ------------------------------------------------------------ which channels, how much

    /** The widening of an edge on {@code sync}'s channel, or null when it is no input or output. */
    private Amount amount(Edge.Sync sync) {
        int[] range = channels(sync.channel());
        if (range == null) {
            return null;
        }
        long low = Long.MAX_VALUE;
        long high = Long.MIN_VALUE;
        Set<String> names = new LinkedHashSet<>();
        String mark = sync.direction() == Edge.Direction.SEND ? "!" : sync.direction() == Edge.Direction.RECEIVE
                ? "?" : "";
        for (int c = range[0]; c < range[0] + range[1]; c++) {
            ObservableChannel input = inputs.get(c);
            ObservableChannel output = outputs.get(c);
            if (input == null && output == null) {
                continue;
            }
            Delay in = input != null && delays.containsKey(input.name()) ? delays.get(input.name()) : inputHull;
            Delay out = output != null && delays.containsKey(output.name()) ? delays.get(output.name()) : outputHull;
            low = Math.min(low, lowOf(in) + lowOf(out));
            high = Math.max(high, highOf(in) + highOf(out));
            names.add(network.channelName(c) + mark);
        }
        return names.isEmpty() ? null : new Amount(low, high, String.join(", ", names));
    }

    private static long lowOf(Delay d) {
        return d == null ? 0 : d.lowMicros();
    }

    private static long highOf(Delay d) {
        return d == null ? 0 : d.highMicros();
    }

    /**
     * The channels a synchronisation's channel expression may name, as {first, count}: one channel, one element
     * of an array at a constant index, or a whole array (or a part of one) at an index known only when running.
     */
    private static int[] channels(Expression e) {
        if (e instanceof Expression.ChannelRef r) {
            ChannelVariable c = r.channel();
            return new int[] {c.index(), c.type().channels()};
        }
        if (e instanceof Expression.Index ix && ix.array().type() instanceof Type.Array a) {
            int[] whole = channels(ix.array());
            if (whole == null) {
                return null;
            }
            int element = a.element().channels();
            if (ix.index() instanceof Expression.Constant k) {
                return new int[] {whole[0] + (k.value() - a.firstIndex()) * element, element};
            }
            return whole;
        }
        return null;
    }

    // ------------------------------------------------------------ finding the bounds

    private void recordUsers(Expression e, Process p) {
        if (e instanceof Expression.Binary b && (b.op() == Expression.Operator.AND
                || b.op() == Expression.Operator.OR)) {
            recordUsers(b.left(), p);
            recordUsers(b.right(), p);
        } else if (e instanceof Expression.Binary b && b.type() instanceof Type.ClockConstraint) {
            users.computeIfAbsent(b.pos().fragment().fileOffset(b.pos().start()), k -> new LinkedHashSet<>())
                    .add(p.name());
        }
    }

    /** Records the clock comparisons of a guard or invariant of an observable edge. */
    private void visit(Expression e, boolean invariant, Process p, Amount amount, String place) {
        if (!(e instanceof Expression.Binary b)) {
            return;
        }
        if (b.op() == Expression.Operator.AND || b.op() == Expression.Operator.OR) {
            visit(b.left(), invariant, p, amount, place);
            visit(b.right(), invariant, p, amount, place);
            return;
        }
        if (!(b.type() instanceof Type.ClockConstraint)) {
            return;
        }
        Bound bound = bounds.computeIfAbsent(b.pos().fragment().fileOffset(b.pos().start()),
                k -> classify(b, invariant, p.template(), place));
        bound.channels.add(amount.channels());
        bound.processes.add(p.name());
        bound.lowMicros = Math.min(bound.lowMicros, amount.lowMicros());
        bound.highMicros = Math.max(bound.highMicros, amount.highMicros());
    }

    private Bound classify(Expression.Binary b, boolean invariant, String template, String place) {
        Bound bound = new Bound(b, template, place);
        Type lt = b.left().type();
        Type rt = b.right().type();
        if (b.op() == Expression.Operator.IMPLY) {
            bound.leftReason = "an implication of clock constraints is not a bound";
        } else if (lt instanceof Type.ClockDifference || rt instanceof Type.ClockDifference
                || lt instanceof Type.Clock && rt instanceof Type.Clock) {
            bound.leftReason = "a clock difference is not widened (it does not bound the delay of one event)";
        } else {
            boolean clockLeft = lt instanceof Type.Clock;
            bound.clock = clockLeft ? b.left() : b.right();
            bound.bound = clockLeft ? b.right() : b.left();
            bound.kind = kindOf(b.op(), clockLeft);
            if (bound.kind == null) {
                bound.leftReason = "'" + symbol(b.op()) + "' on a clock is not a bound";
            } else if (!(bound.bound instanceof Expression.Constant) || !shiftedByConstants(bound.clock)) {
                bound.leftReason = "the bound is not a constant expression";
            } else if (bound.bound.pos().fragment() != b.pos().fragment()) {
                bound.leftReason = "the bound is written outside this label (a reference parameter)";
            } else if (invariant && bound.kind != Kind.UPPER) {
                bound.leftReason = "only upper bounds of an invariant are widened";
            }
        }
        return bound;
    }

    private static Kind kindOf(Expression.Operator op, boolean clockLeft) {
        return switch (op) {
            case GE, GT -> clockLeft ? Kind.LOWER : Kind.UPPER;
            case LE, LT -> clockLeft ? Kind.UPPER : Kind.LOWER;
            case EQ -> Kind.EQUAL;
            default -> null;
        };
    }

    /** Whether a clock-typed expression is a clock, possibly plus or minus constants ({@code x + 2}). */
    private static boolean shiftedByConstants(Expression e) {
        if (e instanceof Expression.Binary b) {
            return b.left().type() instanceof Type.Clock ? shiftedByConstants(b.left()) && b.right().isConstant()
                    : shiftedByConstants(b.right()) && b.left().isConstant();
        }
        return e.type() instanceof Type.Clock;
    }

    private static String symbol(Expression.Operator op) {
        return switch (op) {
            case NE -> "!=";
            case LT -> "<";
            case LE -> "<=";
            case GE -> ">=";
            case GT -> ">";
            case EQ -> "==";
            default -> op.name();
        };
    }

    private String roundingReason(Bound b) {
        boolean lower = b.kind == Kind.LOWER && lowerUnits(b) == 0;
        boolean upper = b.kind == Kind.UPPER && upperUnits(b) == 0;
        if (b.kind == Kind.EQUAL && lowerUnits(b) == 0 && upperUnits(b) == 0 || upper) {
            return "no delay is given for this edge's channels";
        }
        if (lower) {
            return b.lowMicros == 0 ? "the shortest delays of this edge's channels are 0 us"
                    : "the lower bound's widening of " + b.lowMicros + " us rounds down to 0 time units";
        }
        return null;
    }

    private long lowerUnits(Bound b) {
        return Math.floorDiv(b.lowMicros, unit);
    }

    private long upperUnits(Bound b) {
        return -Math.floorDiv(-b.highMicros, unit);
    }

    // ------------------------------------------------------------ editing

    /** Adds the edits that widen {@code b} and returns the comparison's new text. */
    private String edit(Bound b, List<Edit> edits) {
        Pos cmp = b.comparison.pos();
        Fragment f = cmp.fragment();
        checkSource(cmp);
        int value = ((Expression.Constant) b.bound).value();
        long low = lowerUnits(b);
        long high = upperUnits(b);
        if (b.kind == Kind.EQUAL) {
            String clock = raw(b.clock.pos());
            String bound = raw(grouped(b.bound.pos()));
            String bare = grouped(b.bound.pos()).text();
            int at = f.fileOffset(cmp.start());
            String plain = "(" + b.clock.pos().text() + " >= " + plus(bare, low, value) + " && "
                    + b.clock.pos().text() + " <= " + plus(bare, high, value) + ")";
            String escaped = "(" + clock + escape(" >= ", at) + plus(bound, low, value)
                    + escape(" && ", at) + clock + escape(" <= ", at) + plus(bound, high, value)
                    + ")";
            edits.add(new Edit(f.fileOffset(cmp.start()), endOffset(cmp), escaped));
            return plain;
        }
        long amount = b.kind == Kind.LOWER ? low : high;
        Pos bound = grouped(b.bound.pos());
        boolean atom = isAtom(bound.text());
        String suffix = (atom ? "" : ")") + " + " + checkedAmount(amount, value, bound);
        if (!atom) {
            edits.add(new Edit(f.fileOffset(bound.start()), f.fileOffset(bound.start()), "("));
        }
        edits.add(new Edit(endOffset(bound), endOffset(bound), suffix));
        String t = f.text();
        return t.substring(cmp.start(), bound.start()) + (atom ? "" : "(") + bound.text() + suffix
                + t.substring(bound.end(), Math.max(bound.end(), cmp.end()));
    }

    private String plus(String bound, long amount, int value) {
        if (amount == 0) {
            return bound;
        }
        return (isAtom(bound) ? bound : "(" + bound + ")") + " + " + checkedAmount(amount, value, null);
    }

    private static long checkedAmount(long amount, int value, Pos at) {
        if (value + amount > Integer.MAX_VALUE) {
            throw new IllegalArgumentException((at == null ? "a bound" : "the bound " + at.text() + " at " + at)
                    + " widened by " + amount + " time units does not fit in 32 bits; use a larger time unit");
        }
        return amount;
    }

    /** Whether {@code s} needs no parentheses before {@code + n}: a name, a number, or one parenthesised group. */
    private static boolean isAtom(String s) {
        String t = s.trim();
        if (ATOM.matcher(t).matches()) {
            return true;
        }
        if (!t.startsWith("(") || !t.endsWith(")")) {
            return false;
        }
        int depth = 0;
        for (int i = 0; i < t.length(); i++) {
            depth += t.charAt(i) == '(' ? 1 : t.charAt(i) == ')' ? -1 : 0;
            if (depth == 0 && i < t.length() - 1) {
                return false;
            }
        }
        return true;
    }

    /**
     * {@code pos} with the parentheses written around it: the parser keeps an expression's position without
     * them, and the widening goes after the closing one.
     */
    private static Pos grouped(Pos pos) {
        String t = pos.fragment().text();
        int start = pos.start();
        int end = pos.end();
        while (true) {
            int i = start - 1;
            while (i >= 0 && Character.isWhitespace(t.charAt(i))) {
                i--;
            }
            int j = end;
            while (j < t.length() && Character.isWhitespace(t.charAt(j))) {
                j++;
            }
            if (i < 0 || j >= t.length() || t.charAt(i) != '(' || t.charAt(j) != ')') {
                return new Pos(pos.fragment(), start, end);
            }
            start = i;
            end = j + 1;
        }
    }

    /** The file's own characters of {@code pos}. */
    private String raw(Pos pos) {
        return text.substring(pos.fragment().fileOffset(pos.start()), endOffset(pos));
    }

    /**
     * The file offset just after the last character of {@code pos} (of its entity reference, or of its
     * {@code \r\n}): not the offset of the character after it, which may lie beyond the end of a CDATA section.
     */
    private int endOffset(Pos pos) {
        if (pos.end() <= pos.start()) {
            return pos.fragment().fileOffset(pos.start());
        }
        int last = pos.fragment().fileOffset(pos.end() - 1);
        if (xml && text.charAt(last) == '&') {
            return text.indexOf(';', last) + 1;
        }
        return text.startsWith("\r\n", last) ? last + 2 : last + 1;
    }

    /** Checks that the file holds the text the network was loaded from at {@code pos}. */
    private void checkSource(Pos pos) {
        String raw = raw(pos);
        String decoded = xml ? unescape(raw) : raw;
        if (!decoded.equals(pos.text())) {
            throw new IllegalArgumentException("the network was not loaded from this text: at " + pos + " it has '"
                    + oneLine(pos.text()) + "', the text '" + oneLine(raw) + "'");
        }
    }

    private static String unescape(String raw) {
        return raw.replaceAll("(?s)<!--.*?-->", "").replace("<![CDATA[", "").replace("]]>", "")
                .replace("\r\n", "\n").replace('\r', '\n')
                .replace("&lt;", "<").replace("&gt;", ">").replace("&quot;", "\"").replace("&apos;", "'")
                .replace("&amp;", "&");
    }

    /**
     * {@code s} as the file writes text at {@code offset}: in XML, escaped outside CDATA sections ({@code >} only
     * when the file escapes it).
     */
    private String escape(String s, int offset) {
        if (!xml || text.lastIndexOf("<![CDATA[", offset) > text.lastIndexOf("]]>", offset)) {
            return s;
        }
        String escaped = s.replace("&", "&amp;").replace("<", "&lt;");
        return text.contains("&gt;") ? escaped.replace(">", "&gt;") : escaped;
    }

    private String apply(List<Edit> edits) {
        edits.sort((a, b) -> a.start != b.start ? Integer.compare(b.start, a.start) : Integer.compare(b.end, a.end));
        StringBuilder out = new StringBuilder(text);
        for (Edit e : edits) {
            out.replace(e.start, e.end, e.raw);
        }
        return out.toString();
    }

    // ------------------------------------------------------------ the comment

    private Edit note(List<Change> changes, List<Left> left) {
        StringBuilder note = new StringBuilder();
        note.append("// Delta-extended by dtron delta (DTRON thesis, section 3.5) with ").append(oneLine(source))
                .append(".\n");
        note.append("// Time unit ").append(unit).append(" us. Delays, low..high in us (in time units, low rounded"
                + " down, high up):\n");
        for (ObservableChannel c : testInterface.inputs()) {
            delayLine(note, "input", c);
        }
        for (ObservableChannel c : testInterface.outputs()) {
            delayLine(note, "output", c);
        }
        note.append("// On each edge of an input or output: lower clock bounds of its guard + (low_in + low_out),\n"
                + "// upper bounds of its guard and of its source location's invariant + (high_in + high_out);\n"
                + "// the edge's own channel gives the interval of its direction, the hull of the channels given\n"
                + "// the other one (0 when none is given).\n");
        note.append("// Widened ").append(changes.size()).append(changes.size() == 1 ? " bound" : " bounds")
                .append(changes.isEmpty() ? "." : " (at the lines of the model before this comment):").append('\n');
        int listed = 0;
        for (Change c : changes) {
            if (listed++ == MAX_LISTED) {
                note.append("//   and ").append(changes.size() - MAX_LISTED).append(" more\n");
                break;
            }
            note.append("//   ").append(c.place()).append(": ").append(c.before()).append("  ->  ").append(c.after())
                    .append('\n');
        }
        if (!left.isEmpty()) {
            note.append("// Left ").append(left.size()).append(left.size() == 1 ? " clock comparison" :
                    " clock comparisons").append(" as written:\n");
            listed = 0;
            for (Left l : left) {
                if (listed++ == MAX_LISTED) {
                    note.append("//   and ").append(left.size() - MAX_LISTED).append(" more\n");
                    break;
                }
                note.append("//   ").append(l.place()).append(": ").append(l.text()).append(": ").append(l.reason())
                        .append('\n');
            }
        }
        int at = noteOffset();
        String lines = text.contains("\r\n") ? note.toString().replace("\n", "\r\n") : note.toString();
        return new Edit(at, at, escape(lines, at));
    }

    private void delayLine(StringBuilder note, String direction, ObservableChannel c) {
        Delay d = delays.get(c.name());
        if (d != null) {
            note.append("//   ").append(direction).append(' ').append(c.name()).append(' ').append(d.lowMicros())
                    .append("..").append(d.highMicros()).append(" us (").append(Math.floorDiv(d.lowMicros(), unit))
                    .append("..").append(-Math.floorDiv(-d.highMicros(), unit)).append(" units)\n");
        }
    }

    /**
     * Where the comment goes: the start of an XTA file, or the start of the global declarations of an XML model
     * (of the section that declares the interface's channels when there are none).
     */
    private int noteOffset() {
        if (!xml) {
            return 0;
        }
        List<Pos> globals = new ArrayList<>();
        network.variables().stream().filter(v -> v.owner() == null).forEach(v -> globals.add(v.pos()));
        network.clocks().stream().filter(v -> v.owner() == null).forEach(v -> globals.add(v.pos()));
        network.channels().stream().filter(v -> v.owner() == null).forEach(v -> globals.add(v.pos()));
        Fragment declarations = null;
        for (Pos p : globals) {
            if (p != null && p.fragment().template() == null && "declaration".equals(p.fragment().kind())) {
                declarations = p.fragment();
                break;
            }
        }
        if (declarations == null) {
            List<ObservableChannel> all = new ArrayList<>(testInterface.inputs());
            all.addAll(testInterface.outputs());
            declarations = network.channelVariableOf(all.get(0).channel()).pos().fragment();
        }
        return declarations.fileOffset(0);
    }

    private static String oneLine(String s) {
        return s.strip().replaceAll("\\s+", " ");
    }
}
