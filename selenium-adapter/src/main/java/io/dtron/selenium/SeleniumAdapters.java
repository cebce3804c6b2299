package io.dtron.selenium;

import com.google.inject.AbstractModule;
import com.google.inject.ConfigurationException;
import com.google.inject.CreationException;
import com.google.inject.Guice;
import com.google.inject.Injector;
import com.google.inject.ProvisionException;
import com.google.inject.Scopes;
import com.google.inject.name.Names;
import com.google.inject.spi.Message;
import io.dtron.api.Dtron;
import io.dtron.api.DtronAdapter;
import io.dtron.selenium.internal.ClassScanner;
import io.dtron.selenium.internal.Locators;
import io.dtron.selenium.internal.Messages;
import io.dtron.selenium.internal.StepWatch;
import io.dtron.selenium.internal.UserSessions;
import java.io.IOException;
import java.io.InputStream;
import java.io.InputStreamReader;
import java.io.Reader;
import java.lang.reflect.Modifier;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.Collection;
import java.util.HashMap;
import java.util.LinkedHashMap;
import java.util.LinkedHashSet;
import java.util.List;
import java.util.Map;
import java.util.Objects;
import java.util.Properties;
import java.util.Set;
import java.util.concurrent.atomic.AtomicBoolean;
import java.util.stream.Collectors;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * A set of Selenium adapters, found in a package or listed, created with Guice and started on a bus: a
 * {@link DtronAdapter}, so {@code dtron run MODEL --adapter io.dtron.selenium.SeleniumAdapters:com.example.web}
 * tests a web application with the adapters of package {@code com.example.web}.
 *
 * <p>The properties that {@code @Inject @Named("KEY") String} fields and constructor parameters receive, and
 * that {@link AbstractSeleniumAdapter#findElement} looks locators up in, come from, by increasing precedence:
 * the file {@value #PROPERTIES_FILE} in each scanned package (a class-path resource), the files given to
 * {@link Builder#properties(Path)}, a system property with the name of a key already defined, and
 * {@link Builder#property}. Each adapter class is created once, so adapters injected into each other are the
 * ones that serve their channels. Closing stops the adapters and quits the browsers.
 *
 * <p>Besides the adapters' own keys, the properties may set {@value #BROWSERS_PROPERTY} and
 * {@value #START_PAGE_PROPERTY} (browsers started, and a page loaded in each, before the run),
 * {@value #SLOW_STEP_PROPERTY} (when a step still running is logged with the WebDriver call it waits for) and
 * {@value #STEP_TIMEOUT_PROPERTY} (when a step is given up). A step given up, or one that fails on the adapters'
 * own machinery (a browser that does not start or is gone, chromedriver not answering, a WebDriver call that
 * timed out), reports no result: the adapters log the user, the step and what it waited for and leave the bus,
 * so that the tester ends the run INCONCLUSIVE rather than FAILED.
 */
public final class SeleniumAdapters implements DtronAdapter {
    /** The properties file read from each scanned package. */
    public static final String PROPERTIES_FILE = "adapters.properties";
    /**
     * The property that says how many browsers to start before the run (users 0 to N - 1), when the builder's
     * {@link Builder#browsers} is not called: so that {@code dtron run --adapter SeleniumAdapters:PACKAGE} does
     * not make the first steps of a test wait for their browser to start.
     */
    public static final String BROWSERS_PROPERTY = "dtron.browsers";
    /**
     * The property that says after how many milliseconds a step still running is logged with what it is doing
     * (the WebDriver call it waits for), and a step that took as long is logged with its times (default
     * {@value #DEFAULT_SLOW_STEP_MILLIS}).
     */
    public static final String SLOW_STEP_PROPERTY = "dtron.slowStepMillis";
    /** The default of {@link #SLOW_STEP_PROPERTY}. */
    public static final long DEFAULT_SLOW_STEP_MILLIS = 2000;
    /**
     * The property that bounds a step, in milliseconds (default {@value #DEFAULT_STEP_TIMEOUT_MILLIS}): a step
     * still running then is given up, with the user, the step and the WebDriver call it waits for in the log, and
     * the adapters leave the bus, so that the tester ends the run INCONCLUSIVE; its result never comes.
     */
    public static final String STEP_TIMEOUT_PROPERTY = "dtron.stepTimeoutMillis";
    /** The default of {@link #STEP_TIMEOUT_PROPERTY}. */
    public static final long DEFAULT_STEP_TIMEOUT_MILLIS = 30_000;
    /**
     * The property that names the page every browser opens when it starts, when the builder's
     * {@link Builder#startPage} is not called: with {@value #BROWSERS_PROPERTY}, the browsers load it before the
     * run, so that the first steps do not pay for a browser's first page load.
     */
    public static final String START_PAGE_PROPERTY = "dtron.startPage";

    private static final Logger LOG = LoggerFactory.getLogger(SeleniumAdapters.class);

    private final Map<String, String> properties;
    private final WebDriverFactory driverFactory;
    private final String startPage;
    private final int prestartBrowsers;
    private final long slowStepMillis;
    private final long stepTimeoutMillis;
    private final AtomicBoolean gaveUp = new AtomicBoolean();
    private volatile Dtron dtron;
    private final List<AbstractSeleniumAdapter> adapters;
    private UserSessions sessions;
    private boolean started;
    private boolean closed;

    /**
     * Creates the adapters of a package with the package's {@value #PROPERTIES_FILE} and headless Chromium: the
     * constructor {@code dtron run --adapter io.dtron.selenium.SeleniumAdapters:PACKAGE} calls.
     *
     * @throws IllegalArgumentException if the package has no adapter, or one cannot be created (a missing
     *                                  property, two adapters of one channel), saying why
     */
    public SeleniumAdapters(String packageName) {
        this(builder().scan(packageName));
    }

    private SeleniumAdapters(Builder builder) {
        if (builder.types.isEmpty()) {
            throw new IllegalArgumentException("no adapters: scan a package or add adapter classes");
        }
        this.properties = builder.resolveProperties();
        this.driverFactory = builder.driverFactory;
        this.startPage = builder.startPage != null ? builder.startPage : properties.get(START_PAGE_PROPERTY);
        this.prestartBrowsers = builder.prestartBrowsers != null ? builder.prestartBrowsers
                : browsersProperty(properties);
        this.slowStepMillis = positiveProperty(properties, SLOW_STEP_PROPERTY, DEFAULT_SLOW_STEP_MILLIS);
        this.stepTimeoutMillis = positiveProperty(properties, STEP_TIMEOUT_PROPERTY, DEFAULT_STEP_TIMEOUT_MILLIS);
        if (stepTimeoutMillis < slowStepMillis) {
            throw new IllegalArgumentException("property " + STEP_TIMEOUT_PROPERTY + " (" + stepTimeoutMillis
                    + " ms) is below " + SLOW_STEP_PROPERTY + " (" + slowStepMillis + " ms)");
        }
        this.adapters = create(builder.types, properties);
    }

    private static int browsersProperty(Map<String, String> properties) {
        String value = properties.get(BROWSERS_PROPERTY);
        if (value == null) {
            return 0;
        }
        try {
            int users = Integer.parseInt(value.strip());
            if (users >= 0) {
                return users;
            }
        } catch (NumberFormatException e) {
            // refused below
        }
        throw new IllegalArgumentException("property " + BROWSERS_PROPERTY + " = '" + value + "': give the number"
                + " of browsers to start before the run (0 or more)");
    }

    private static long positiveProperty(Map<String, String> properties, String key, long defaultValue) {
        String value = properties.get(key);
        if (value == null) {
            return defaultValue;
        }
        try {
            long n = Long.parseLong(value.strip());
            if (n > 0) {
                return n;
            }
        } catch (NumberFormatException e) {
            // refused below
        }
        throw new IllegalArgumentException("property " + key + " = '" + value + "': give a positive number of"
                + " milliseconds");
    }

    /** Returns a builder. */
    public static Builder builder() {
        return new Builder();
    }

    private static List<AbstractSeleniumAdapter> create(Collection<Class<? extends AbstractSeleniumAdapter>> types,
                                                        Map<String, String> properties) {
        Map<String, Class<?>> byChannel = new HashMap<>();
        for (Class<? extends AbstractSeleniumAdapter> type : types) {
            String channel = AbstractSeleniumAdapter.channelOf(type).getChannelName();
            Class<?> other = byChannel.putIfAbsent(channel, type);
            if (other != null) {
                throw new IllegalArgumentException("adapters " + other.getName() + " and " + type.getName()
                        + " both serve channel '" + channel + "'");
            }
        }
        try {
            Injector injector = Guice.createInjector(new AbstractModule() {
                @Override
                protected void configure() {
                    Properties values = new Properties();
                    values.putAll(properties);
                    Names.bindProperties(binder(), values);
                    types.forEach(type -> bind(type).in(Scopes.SINGLETON));
                }
            });
            List<AbstractSeleniumAdapter> created = new ArrayList<>();
            types.forEach(type -> created.add(injector.getInstance(type)));
            return List.copyOf(created);
        } catch (CreationException e) {
            throw new IllegalArgumentException(guiceMessage(e.getErrorMessages()), e);
        } catch (ConfigurationException e) {
            throw new IllegalArgumentException(guiceMessage(e.getErrorMessages()), e);
        } catch (ProvisionException e) {
            throw new IllegalArgumentException(guiceMessage(e.getErrorMessages()), e);
        }
    }

    private static String guiceMessage(Collection<Message> messages) {
        return "cannot create the adapters: " + messages.stream().map(Message::getMessage)
                .map(Messages::firstLine).collect(Collectors.joining("; "));
    }

    /**
     * Starts the adapters on a bus member: starts the browsers of {@link Builder#browsers}, then listens to the
     * adapters' channels.
     *
     * @throws AdapterException      if a browser cannot be started
     * @throws IllegalStateException if started twice, or after closing
     */
    @Override
    public synchronized void start(Dtron dtron) {
        Objects.requireNonNull(dtron, "dtron");
        if (started || closed) {
            throw new IllegalStateException("the adapters can be started once");
        }
        started = true;
        this.dtron = dtron;
        sessions = new UserSessions(driverFactory, startPage, new StepWatch(slowStepMillis, stepTimeoutMillis,
                this::giveUp));
        AdapterRuntime runtime = new AdapterRuntime(dtron, sessions, new Locators(properties), this::giveUp,
                gaveUp::get);
        try {
            long begin = System.nanoTime();
            sessions.prestart(prestartBrowsers);
            if (prestartBrowsers > 0) {
                LOG.info("Started the browsers of users 0 to {} in {} ms{}; a user from {} on starts its browser in"
                        + " its first step", prestartBrowsers - 1, (System.nanoTime() - begin) / 1_000_000,
                        startPage == null ? "" : ", each with " + startPage, prestartBrowsers);
            }
            adapters.forEach(a -> a.attach(runtime));
        } catch (RuntimeException e) {
            close();
            throw e;
        }
        LOG.info("Started Selenium adapters {} on {}", adapters, dtron);
    }

    /**
     * The adapters' own machinery failed or a step outlived the step timeout: logs why, stops listening and leaves
     * the bus, so that the tester ends the run INCONCLUSIVE (a member of the system under test left) instead of
     * taking the missing result for a fault of the system under test. Once per run.
     */
    private void giveUp(String reason) {
        if (!gaveUp.compareAndSet(false, true)) {
            LOG.info("Also: {}", reason);
            return;
        }
        LOG.error("{}. No result can be reported for it that would not blame the system under test for what may"
                + " be the adapters' own trouble: the Selenium adapters stop and leave the bus, so that the run ends"
                + " INCONCLUSIVE", reason);
        adapters.forEach(AbstractSeleniumAdapter::detach);
        Dtron member = dtron;
        // not on a user's thread or the bus's: closing the member waits for its listeners
        Thread leave = new Thread(member::close, "selenium-give-up");
        leave.setDaemon(true);
        leave.start();
    }

    /** Returns the adapters, sorted by class name. */
    public List<AbstractSeleniumAdapter> getAdapters() {
        return adapters;
    }

    /**
     * Returns the adapter of a class.
     *
     * @throws IllegalArgumentException if it is not one of these adapters
     */
    public <T extends AbstractSeleniumAdapter> T getAdapter(Class<T> type) {
        return adapters.stream().filter(type::isInstance).map(type::cast).findFirst()
                .orElseThrow(() -> new IllegalArgumentException(type.getName() + " is not one of " + adapters));
    }

    /** Stops listening, lets the steps under way finish (a few seconds at most) and quits the browsers. */
    @Override
    public synchronized void close() {
        if (closed) {
            return;
        }
        closed = true;
        if (sessions != null) {
            adapters.forEach(AbstractSeleniumAdapter::detach);
            sessions.close(!gaveUp.get());
        }
    }

    @Override
    public String toString() {
        return "SeleniumAdapters" + adapters;
    }

    /** Builds {@link SeleniumAdapters}. Not thread-safe. */
    public static final class Builder {
        private final Set<Class<? extends AbstractSeleniumAdapter>> types = new LinkedHashSet<>();
        private final List<Map<String, String>> resources = new ArrayList<>();
        private final List<Path> files = new ArrayList<>();
        private final Map<String, String> explicit = new LinkedHashMap<>();
        private WebDriverFactory driverFactory = HeadlessChrome.defaults();
        private String startPage;
        private Integer prestartBrowsers;

        private Builder() {
        }

        /**
         * Adds every adapter class of a package (not of its subpackages): the concrete top-level and static
         * nested classes extending {@link AbstractSeleniumAdapter}; and the package's {@value #PROPERTIES_FILE},
         * if it has one.
         *
         * @throws IllegalArgumentException if the package has no adapter class
         */
        public Builder scan(String packageName) {
            ClassLoader loader = loader();
            List<Class<? extends AbstractSeleniumAdapter>> found = new ArrayList<>();
            for (Class<?> type : ClassScanner.classesIn(packageName, loader)) {
                if (isAdapter(type)) {
                    found.add(type.asSubclass(AbstractSeleniumAdapter.class));
                }
            }
            if (found.isEmpty()) {
                throw new IllegalArgumentException("no adapters in package " + packageName + ": no concrete class"
                        + " there extends " + AbstractSeleniumAdapter.class.getName());
            }
            types.addAll(found);
            String resource = packageName.replace('.', '/') + "/" + PROPERTIES_FILE;
            try (InputStream in = loader.getResourceAsStream(resource)) {
                if (in != null) {
                    resources.add(load(new InputStreamReader(in, StandardCharsets.UTF_8), resource));
                }
            } catch (IOException e) {
                throw new IllegalArgumentException("cannot read " + resource + ": " + e.getMessage(), e);
            }
            return this;
        }

        /** Adds one adapter class. */
        public Builder adapter(Class<? extends AbstractSeleniumAdapter> type) {
            if (!isAdapter(Objects.requireNonNull(type, "type"))) {
                throw new IllegalArgumentException(type.getName() + " is no concrete adapter class");
            }
            types.add(type);
            return this;
        }

        /** Adds a properties file (UTF-8), whose values override the packages' {@value #PROPERTIES_FILE}. */
        public Builder properties(Path file) {
            files.add(Objects.requireNonNull(file, "file"));
            return this;
        }

        /** Sets one property, overriding every other source. */
        public Builder property(String key, String value) {
            explicit.put(Objects.requireNonNull(key, "key"), Objects.requireNonNull(value, "value"));
            return this;
        }

        /** Sets how browsers are started (default: {@link HeadlessChrome#defaults()}). */
        public Builder driverFactory(WebDriverFactory factory) {
            driverFactory = Objects.requireNonNull(factory, "factory");
            return this;
        }

        /**
         * Starts the browsers of users 0 to {@code users - 1} when the adapters start, in parallel, rather than
         * at each user's first message (default: the property {@value #BROWSERS_PROPERTY}, else none ahead).
         */
        public Builder browsers(int users) {
            if (users < 0) {
                throw new IllegalArgumentException("users must not be negative: " + users);
            }
            prestartBrowsers = users;
            return this;
        }

        /**
         * Sets the page every browser opens when it starts (default: the property {@value #START_PAGE_PROPERTY},
         * else none, a blank page). With {@link #browsers}, the first steps of a test then find the browsers warmed
         * up: a browser's first page load (its renderer starting) takes seconds on a busy machine, and would else
         * count against the system under test in the first step of each user.
         */
        public Builder startPage(String url) {
            startPage = Objects.requireNonNull(url, "url");
            return this;
        }

        /**
         * Finds the properties and creates the adapters, not yet started.
         *
         * @throws IllegalArgumentException if there is no adapter, or one cannot be created, saying why
         */
        public SeleniumAdapters build() {
            return new SeleniumAdapters(this);
        }

        private Map<String, String> resolveProperties() {
            Map<String, String> values = new LinkedHashMap<>();
            resources.forEach(values::putAll);
            for (Path file : files) {
                try (Reader in = Files.newBufferedReader(file, StandardCharsets.UTF_8)) {
                    values.putAll(load(in, file.toString()));
                } catch (IOException e) {
                    throw new IllegalArgumentException("cannot read properties " + file + ": " + e.getMessage(), e);
                }
            }
            values.replaceAll(System::getProperty);
            values.putAll(explicit);
            return values;
        }

        private static Map<String, String> load(Reader in, String name) throws IOException {
            Properties p = new Properties();
            try {
                p.load(in);
            } catch (IllegalArgumentException e) {
                throw new IOException(name + " is malformed: " + e.getMessage(), e);
            }
            Map<String, String> values = new LinkedHashMap<>();
            p.stringPropertyNames().forEach(k -> values.put(k, p.getProperty(k)));
            return values;
        }

        private static boolean isAdapter(Class<?> type) {
            int modifiers = type.getModifiers();
            return AbstractSeleniumAdapter.class.isAssignableFrom(type) && !Modifier.isAbstract(modifiers)
                    && !type.isInterface() && !type.isAnonymousClass() && !type.isLocalClass()
                    && (!type.isMemberClass() || Modifier.isStatic(modifiers));
        }

        private static ClassLoader loader() {
            ClassLoader context = Thread.currentThread().getContextClassLoader();
            return context != null ? context : SeleniumAdapters.class.getClassLoader();
        }
    }
}
