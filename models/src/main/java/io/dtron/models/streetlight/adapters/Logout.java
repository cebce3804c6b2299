package io.dtron.models.streetlight.adapters;

import io.dtron.api.IDtronChannelValued;
import io.dtron.selenium.AbstractSeleniumAdapter;
import io.dtron.selenium.ChannelVariables;
import jakarta.inject.Inject;

/** {@code i_logout(user)}: requires {@link Login}'s post-condition, logs out and expects the login form. */
@ChannelVariables("user")
public final class Logout extends AbstractSeleniumAdapter {
    private final Login login;

    /** The adapter, with the login adapter whose post-condition it checks. */
    @Inject
    public Logout(Login login) {
        this.login = login;
    }

    @Override
    protected void execute(IDtronChannelValued message) {
        login.requireLoggedIn();
        findElement("LOGOUT_LINK").click();
        findElement("LOGIN_BUTTON");
    }
}
